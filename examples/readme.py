import numpy as np, matplotlib.pyplot as plt, stickslip

paper = stickslip.Model("paper")
motion = paper.simulate(W=5, Q0=70)  # from rest until it settles
print(motion.structure, "N =", motion.N, "|λ| =", abs(motion.eigenvalues))
h = motion.history(periods=2)  # numpy arrays t, Wt, x, v, a, F, domain
sweep = paper.sweep("W", np.linspace(0.2, 9, 200), Q0=70)  # the main job
df = sweep.to_pandas()  # one row per motion and W
fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
a.plot(h.x, h.v); a.set(xlabel="x", ylabel="v", title=motion.structure)
b.scatter(df.W, df.start_x, c=df.stable, s=4, cmap="coolwarm_r"); b.set(xlabel="W", ylabel="x at the first switching point")
fig.savefig("docs/guide/src/figures/python_example.png", dpi=90)
