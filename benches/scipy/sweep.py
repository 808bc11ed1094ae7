#!/usr/bin/env python3
"""The SciPy baseline of stickslip's main job.

What a careful user writes today to get the steady motions of the paper model
(`models/paper.ssm`, SPEC §1-§3) along the forcing frequency: for each of the
200 values W = 0.2 ... 9 at Q0 = 70 (every other parameter at the model's
default), simulate to the steady state with

* `scipy.integrate.solve_ivp(method="DOP853", rtol=1e-10, atol=1e-12)` inside
  each friction domain (one right-hand side per domain, its constants computed
  once: the friction piece is affine, folded into an effective damping and a
  constant);
* event location at the boundaries v = V (Sigma1), V1 (Sigma2), V2 (Sigma3):
  one terminal event function per boundary the domain can reach, with the
  direction of arrival; at each crossing the integration restarts on the other
  side with the other friction piece;
* stick by the force criteria of SPEC §3 at Sigma1: arrival from above passes
  into Omega3 if F1_in < 0 and F3_in < 0, arrival from below passes into Omega1
  if both are > 0, otherwise the mass sticks (x = x_i + V (t - t_i)); the
  stick lasts while |Fnf| < as and ends at the first root of Fnf = +as (into
  Omega1) or Fnf = -as (into Omega3). While stuck Fnf is an explicit function
  of t, so its first root is located exactly: the extrema of Fnf are known in
  closed form, every monotone piece between them is tested and the crossing
  refined by `scipy.optimize.brentq`.

Steady state: the stroboscopic map (W t = 2 pi k) is sampled every forcing
period; the motion has settled with period N (N = 1 ... 8) as soon as the
last N stroboscopic points repeat the N before them to `--tol` (1e-7, max norm
on (x, v)). The cap is 1500 forcing periods, the cap `stickslip sweep` uses.
For every W the result is the period N, the stroboscopic point, the boundary
events of one cycle and the structure in stickslip's notation (`P_{sigma_m
... sigma_1}`, applied right to left: `3_31` is domain 3 from Sigma1 to
Sigma3, `0_11` a stick on Sigma1), "NM" (the steady motion touches no
boundary), or "unsettled" (no repetition within the cap).

Start: by default each W continues from the previous W's steady state (the
state at W t = 0 of the last settled cycle), as a user sweeping a parameter
does to shorten the transients (and as a physical slow sweep would); the
first W starts from rest. `--start rest` starts every W from rest instead
(what `stickslip simulate` does).

`--check stickslip.json` compares a result file (or this run) with
`stickslip sweep ... --json`: the simulated steady motion must be one of the
stable motions stickslip reports at that W (same N, one of its switching
points within `--check-tol` of stickslip's start point, same structure up to
rotation).

Usage:
    python sweep.py [--out result.json] [--count 200] [--from 0.2] [--to 9]
                    [--W 3.7,5] [--start continue|rest]
    python sweep.py --check stickslip.json --result result.json
"""

import argparse
import json
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

TWO_PI = 2.0 * math.pi

# The paper model's defaults (models/paper.ssm).
DEFAULTS = dict(m=5.0, d=0.1, c=30.0, V=3.0, V1=4.5, V2=1.5, mus=0.5, muk=0.4,
                mu1=0.1, mu2=0.5, mu3=0.1, mu4=0.5, g=9.8, Q0=70.0, W=3.0)

STICK = 0
# Boundary k velocity and the domains above / below it.
BOUNDARY_NAMES = {1: "Sigma1", 2: "Sigma2", 3: "Sigma3"}


class Model:
    """The paper model at one parameter set: per-domain constants, events."""

    def __init__(self, p):
        self.p = p
        m, g = p["m"], p["g"]
        fn = m * g
        V, V1, V2 = p["V"], p["V1"], p["V2"]
        mu1, mu2, mu3, mu4, muk = p["mu1"], p["mu2"], p["mu3"], p["mu4"], p["muk"]
        # Kinetic friction per unit mass, one affine piece per domain (SPEC §1).
        friction = {
            2: lambda v: (mu1 * (v - V1) - mu2 * (V1 - V) + fn * muk) / m,
            1: lambda v: (-mu2 * (v - V) + fn * muk) / m,
            3: lambda v: (-mu3 * (v - V) - fn * muk) / m,
            4: lambda v: (mu4 * (v - V2) - mu3 * (V2 - V) - fn * muk) / m,
        }
        self.A0 = p["Q0"] / m
        self.W = p["W"]
        self.c = p["c"]
        self.d = p["d"]
        self.V, self.V1, self.V2 = V, V1, V2
        self.ak = muk * fn / m
        self.as_ = p["mus"] * fn / m
        self.boundary_v = {1: V, 2: V1, 3: V2}
        self.rhs = {}
        self.events = {}
        A0, W, c = self.A0, self.W, self.c
        for j, f in friction.items():
            slope = f(1.0) - f(0.0)
            const = f(0.0)
            k2 = 2.0 * p["d"] + slope  # effective 2 d_j
            self.rhs[j] = self._make_rhs(A0, W, c, k2, const)
        # Terminal events per domain: (boundary, direction of arrival).
        reach = {1: [(1, -1), (2, +1)], 2: [(2, -1)], 3: [(1, +1), (3, -1)], 4: [(3, +1)]}
        for j, bs in reach.items():
            evs = []
            for b, direction in bs:
                ev = self._make_event(self.boundary_v[b])
                ev.terminal = True
                ev.direction = direction
                ev.boundary = b
                evs.append(ev)
            self.events[j] = evs
        # Domain entered when crossing boundary b upwards / downwards.
        self.above = {1: 1, 2: 2, 3: 3}
        self.below = {1: 3, 2: 1, 3: 4}

    @staticmethod
    def _make_rhs(A0, W, c, k2, const):
        cos = math.cos

        def rhs(t, s):
            x, y = s
            return (y, A0 * cos(W * t) - k2 * y - c * x - const)

        return rhs

    @staticmethod
    def _make_event(vb):
        def event(t, s):
            return s[1] - vb

        return event

    def fnf(self, t, x):
        """Non-friction force on Sigma1 (SPEC §3)."""
        return self.A0 * math.cos(self.W * t) - 2.0 * self.d * self.V - self.c * x

    def domain_of(self, t, x, y):
        """Domain (or stick) of a state, deciding on a boundary by the criteria."""
        if y == self.V:
            f = self.fnf(t, x)
            if abs(f) < self.as_:
                return STICK
            return 1 if f > 0 else 3
        if y == self.V1:
            return 2 if self.accel(1, t, x, y) > 0 else 1
        if y == self.V2:
            return 3 if self.accel(4, t, x, y) > 0 else 4
        if y > self.V1:
            return 2
        if y > self.V:
            return 1
        if y > self.V2:
            return 3
        return 4

    def accel(self, j, t, x, y):
        return self.rhs[j](t, (x, y))[1]

    def stick_end(self, t0, x0, t_max):
        """First t > t0 with |Fnf| = as while stuck; (t, side) or None before t_max.

        Fnf(t) = A0 cos(W t) - 2 d V - c (x0 + V (t - t0)) has its extrema where
        sin(W t) = -c V / (A0 W): between them it is monotone, so each piece
        holds at most one root of Fnf - as and one of Fnf + as.
        """
        A0, W, c, V = self.A0, self.W, self.c, self.V
        base = -2.0 * self.d * V - c * x0 + c * V * t0

        def fnf(t):
            return A0 * math.cos(W * t) + base - c * V * t

        # Critical phases of Fnf in [0, 2 pi).
        crit = []
        if A0 != 0.0:
            s = -c * V / (A0 * W)
            if abs(s) <= 1.0:
                a = math.asin(s)
                crit = sorted(((a) % TWO_PI, (math.pi - a) % TWO_PI))
        # Piece ends: the critical times after t0, period by period.
        t_lo, f_lo = t0, fnf(t0)
        k = math.floor(W * t0 / TWO_PI)
        while t_lo < t_max:
            ends = [(k * TWO_PI + ph) / W for ph in crit] + [(k + 1) * TWO_PI / W]
            for t_hi in ends:
                if t_hi <= t_lo:
                    continue
                t_hi = min(t_hi, t_max)
                f_hi = fnf(t_hi)
                for level, side in ((self.as_, 1), (-self.as_, 3)):
                    g_lo, g_hi = f_lo - level, f_hi - level
                    if g_lo == 0.0 and t_lo == t0:
                        continue
                    if g_lo * g_hi <= 0.0 and g_hi != g_lo:
                        tr = brentq(lambda t: fnf(t) - level, t_lo, t_hi, xtol=1e-14, rtol=1e-15)
                        return tr, side
                t_lo, f_lo = t_hi, f_hi
                if t_lo >= t_max:
                    return None
            k += 1
        return None


def settle(model, x0, y0, t0, max_periods, tol, max_n, rtol, atol, chunk):
    """Simulate from (x0, y0) at t0 = 0 to the steady state.

    Returns a dict with the result, plus the state at the last stroboscopic
    time (to continue the next W from).
    """
    W = model.W
    T = TWO_PI / W
    t_cap = max_periods * T
    t, x, y = t0, x0, y0
    dom = model.domain_of(t, x, y)
    strobes = [(x, y)]  # strobe k at t = k T
    events = []  # (t, x, boundary, domain_before, domain_after)
    k_next = 1
    n_rhs = 0
    n_ivp = 0
    result = None

    def spread(n, k):
        """Largest difference between the last n strobes and the n before them."""
        worst = 0.0
        for i in range(n):
            a = strobes[k - i]
            b = strobes[k - i - n]
            worst = max(worst, abs(a[0] - b[0]), abs(a[1] - b[1]))
        return worst

    def settled():
        """The period N if the stroboscopic points repeat, else 0.

        A cycle of N points that nearly repeat with a divisor d of N (closer
        than 1000 tol) is a period-d motion still converging, most often with
        eigenvalues near a root of unity (-1 for N = 2): it is accepted only
        once it repeats to tol / 10, by which time the period-d test has
        passed if d is the period.
        """
        k = len(strobes) - 1
        for n in range(1, max_n + 1):
            if k < 2 * n:
                break
            diff = spread(n, k)
            if diff > tol:
                continue
            near = min((spread(d, k) for d in range(1, n) if n % d == 0), default=math.inf)
            if near < 1e3 * tol and diff > 0.1 * tol:
                return 0
            return n
        return 0

    while t < t_cap and result is None:
        t_end = min((k_next + chunk - 1) * T, t_cap)
        if dom == STICK:
            end = model.stick_end(t, x, t_end)
            t_stop = end[0] if end is not None else t_end
            # Stroboscopic points inside the stick.
            while k_next * T <= t_stop + 1e-15 and result is None:
                ts = k_next * T
                strobes.append((x + model.V * (ts - t), model.V))
                k_next += 1
                n = settled()
                if n:
                    result = n
            if result is not None:
                break
            if end is None:
                x = x + model.V * (t_end - t)
                t = t_end
                continue
            x = x + model.V * (t_stop - t)
            t = t_stop
            y = model.V
            new = 1 if end[1] == 1 else 3
            events.append((t, x, 1, STICK, new))
            dom = new
            continue
        t_eval = [i * T for i in range(k_next, k_next + chunk) if i * T <= t_end and i * T > t]
        sol = solve_ivp(model.rhs[dom], (t, t_end), (x, y), method="DOP853", rtol=rtol, atol=atol,
                        events=model.events[dom], t_eval=t_eval)
        n_ivp += 1
        n_rhs += sol.nfev
        if sol.status == -1:
            raise RuntimeError(f"solve_ivp failed at W = {W}: {sol.message}")
        for i in range(len(sol.t)):
            strobes.append((sol.y[0, i], sol.y[1, i]))
            k_next += 1
            n = settled()
            if n:
                result = n
                break
        if result is not None:
            break
        if sol.status == 1:
            # A boundary reached: which one (the earliest terminal event).
            hit = None
            for ev, te, ye in zip(model.events[dom], sol.t_events, sol.y_events):
                if len(te):
                    if hit is None or te[0] < hit[1]:
                        hit = (ev.boundary, te[0], ye[0])
            b, t, ye = hit
            x = ye[0]
            y = model.boundary_v[b]
            new = transition(model, dom, b, t, x)
            events.append((t, x, b, dom, new))
            dom = new
        else:
            t = sol.t[-1] if len(sol.t) else t_end
            x, y = sol.y[0, -1], sol.y[1, -1]
            t = t_end

    info = {"W": W, "rhs_evaluations": n_rhs, "ivp_calls": n_ivp, "periods": len(strobes) - 1}
    if result is None:
        info.update(kind="unsettled", structure="unsettled")
        return info, strobes[-1]
    n = result
    k = len(strobes) - 1
    t_a, t_b = (k - n) * T, k * T
    cycle = [e for e in events if t_a <= e[0] < t_b]
    info["N"] = n
    info["strobe"] = [list(map(float, s)) for s in strobes[k - n + 1:k + 1]]
    if not cycle:
        info.update(kind="NM", structure="NM")
        return info, strobes[-1]
    # Mapping of each segment, in order of time: from event i to event i+1.
    mappings = []
    for i, e in enumerate(cycle):
        nxt = cycle[(i + 1) % len(cycle)]
        j = e[4]
        mappings.append(f"{j}_{nxt[2]}{e[2]}")
    # Start the cycle where stickslip's structures start: at the flow in
    # Omega4 (4_33) if there is one, else at the smallest name.
    first = mappings.index("4_33") if "4_33" in mappings else mappings.index(min(mappings))
    mappings = mappings[first:] + mappings[:first]
    cycle = cycle[first:] + cycle[:first]
    info.update(
        kind="periodic",
        structure="P_{" + " ".join(reversed(mappings)) + "}",
        points=[{"Wt_mod_2pi": float((W * e[0]) % TWO_PI), "x": float(e[1]),
                 "boundary": BOUNDARY_NAMES[e[2]], "mapping": mp}
                for e, mp in zip(cycle, mappings)],
    )
    return info, strobes[-1]


def transition(model, dom, b, t, x):
    """Domain after arriving on boundary b from domain dom (SPEC §3)."""
    if b != 1:
        # Continuous friction: the flow passes.
        return model.below[b] if dom == model.above[b] else model.above[b]
    f = model.fnf(t, x)
    f1_in, f3_in = f - model.ak, f + model.ak
    if dom == 1:  # from above
        if f1_in < 0 and f3_in < 0:
            return 3
        return STICK
    if f1_in > 0 and f3_in > 0:  # from below
        return 1
    return STICK


def run_sweep(args):
    if args.W:
        ws = [float(w) for w in args.W.split(",")]
    else:
        ws = list(np.linspace(args.w_from, args.w_to, args.count))
    params = dict(DEFAULTS)
    params["Q0"] = args.Q0
    results = []
    state = (0.0, 0.0)
    t_start = time.perf_counter()
    cpu_start = time.process_time()
    for w in ws:
        params["W"] = float(w)
        model = Model(params)
        if args.start == "rest":
            state = (0.0, 0.0)
        t0 = time.perf_counter()
        info, last = settle(model, state[0], state[1], 0.0, args.max_periods, args.tol, args.max_n,
                            args.rtol, args.atol, args.chunk)
        info["seconds"] = time.perf_counter() - t0
        results.append(info)
        state = (float(last[0]), float(last[1]))
        if args.verbose:
            print(f"W = {w:.6f}: {info['structure']} N = {info.get('N', '-')} "
                  f"({info['periods']} periods, {info['rhs_evaluations']} RHS, {info['seconds']:.2f} s)",
                  file=sys.stderr)
    total = time.perf_counter() - t_start
    cpu = time.process_time() - cpu_start
    out = {
        "param": "W",
        "settings": {"method": "DOP853", "rtol": args.rtol, "atol": args.atol, "tol": args.tol,
                     "max_periods": args.max_periods, "max_N": args.max_n, "start": args.start,
                     "Q0": args.Q0},
        "seconds": total,
        "cpu_seconds": cpu,
        "points": results,
    }
    return out


# ---------------------------------------------------------------------------
# Check against stickslip's sweep.


def rotations_equal(a, b):
    if len(a) != len(b):
        return False
    return any(a[i:] + a[:i] == b for i in range(len(a))) if a else True


def parse_structure(s):
    s = s.strip()
    if "^" in s:  # "P_{...}^2": the period, compared separately
        s = s[: s.index("^")]
    if s.startswith("P_{"):
        s = s[3:]
        s = s[: s.index("}")]
    return s.split()


def phase_diff(a, b):
    d = (a - b) % TWO_PI
    return min(d, TWO_PI - d)


def match(sim, motion, tol):
    """(ok, distance, reason) for one simulated result against one stickslip motion."""
    ss = motion.get("structure", "")
    if sim["kind"] == "NM" or ss == "NM":
        if sim["kind"] == "NM" and ss == "NM":
            return True, 0.0, ""
        return False, math.inf, f"simulated {sim['structure']}, stickslip {ss}"
    if motion.get("N", 1) != sim["N"]:
        return False, math.inf, f"N {sim['N']} vs {motion.get('N')}"
    same_structure = rotations_equal(parse_structure(sim["structure"]), parse_structure(ss))
    best = math.inf
    for p in sim["points"]:
        dist = max(phase_diff(p["Wt_mod_2pi"], motion["start_Wt"] % TWO_PI), abs(p["x"] - motion["start_x"]))
        best = min(best, dist)
    if not same_structure:
        return False, best, f"structure {sim['structure']} vs {ss}"
    if best > tol:
        return False, best, f"same structure, switching point {best:.2e} away"
    return True, best, ""


def check(result, reference, tol):
    refs = reference["points"]
    param = reference.get("param", "W")
    counts = {"agree": 0, "coexisting": 0, "disagree": 0, "unsettled": 0}
    worst = 0.0
    listed = []
    for sim in result["points"]:
        w = sim["W"]
        ref = min(refs, key=lambda r: abs(r[param] - w))
        if abs(ref[param] - w) > 1e-9 * max(1.0, abs(w)):
            listed.append(f"W = {w:.9f}: [DISAGREE] no stickslip point at this W")
            counts["disagree"] += 1
            continue
        motions = ref.get("motions", [])
        stable = [mo for mo in motions if mo.get("stable", True)]
        if sim["kind"] == "unsettled":
            counts["unsettled"] += 1
            listed.append(f"W = {w:.9f}: simulation unsettled after {sim['periods']} periods; stickslip: "
                          + ", ".join(f"{mo['structure']} (N={mo.get('N', 1)})" for mo in stable))
            continue
        outcomes = [match(sim, mo, tol) for mo in stable]
        good = [o for o in outcomes if o[0]]
        if good:
            counts["agree"] += 1
            worst = max(worst, min(o[1] for o in good))
            continue
        reasons = "; ".join(f"{mo['structure']} N={mo.get('N', 1)}: {o[2]}" for mo, o in zip(stable, outcomes))
        sim_desc = f"{sim['structure']} N={sim.get('N')}"
        if len(stable) > 1:
            counts["coexisting"] += 1
            listed.append(f"W = {w:.9f}: [coexisting, {len(stable)} stable motions] simulated {sim_desc}; {reasons}")
        else:
            counts["disagree"] += 1
            listed.append(f"W = {w:.9f}: [DISAGREE] simulated {sim_desc}; {reasons or 'stickslip reports no stable motion'}")
    return counts, worst, listed


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--from", dest="w_from", type=float, default=0.2)
    ap.add_argument("--to", dest="w_to", type=float, default=9.0)
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--W", help="comma-separated W values instead of the grid")
    ap.add_argument("--Q0", type=float, default=70.0)
    ap.add_argument("--start", choices=("continue", "rest"), default="continue")
    ap.add_argument("--rtol", type=float, default=1e-10)
    ap.add_argument("--atol", type=float, default=1e-12)
    ap.add_argument("--tol", type=float, default=1e-7, help="stroboscopic repetition tolerance")
    ap.add_argument("--max-periods", type=int, default=1500)
    ap.add_argument("--max-n", type=int, default=8)
    ap.add_argument("--chunk", type=int, default=4, help="forcing periods per solve_ivp call at most")
    ap.add_argument("--out", help="write the result JSON here (default stdout)")
    ap.add_argument("--result", help="with --check: a result file of an earlier run instead of running")
    ap.add_argument("--check", help="stickslip sweep --json output to compare with")
    ap.add_argument("--check-tol", type=float, default=1e-6)
    ap.add_argument("-v", "--verbose", action="store_true")
    args = ap.parse_args()

    if args.result:
        with open(args.result) as fh:
            result = json.load(fh)
    else:
        result = run_sweep(args)
        text = json.dumps(result, indent=1)
        if args.out:
            with open(args.out, "w") as fh:
                fh.write(text + "\n")
        elif not args.check:
            print(text)
        print(f"scipy sweep: {len(result['points'])} W values in {result['seconds']:.2f} s "
              f"(CPU {result['cpu_seconds']:.2f} s)", file=sys.stderr)

    if args.check:
        with open(args.check) as fh:
            reference = json.load(fh)
        counts, worst, listed = check(result, reference, args.check_tol)
        for line in listed:
            print(line)
        total = sum(counts.values())
        print(f"check: {counts['agree']}/{total} agree (largest switching-point distance {worst:.1e}), "
              f"{counts['coexisting']} differ where stickslip reports coexisting stable motions, "
              f"{counts['disagree']} disagree, {counts['unsettled']} unsettled")
        return 1 if counts["disagree"] else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
