#!/usr/bin/env bash
# The Python package's overhead: `simulate` at W = 5, Q0 = 70 (paper model,
# from rest) called from Python against the same work in Rust
# (benches/python_call.rs), in one run; also `Motion.history()`, both
# together, and a trivial call (`stickslip.models()`): the fixed cost of
# crossing into the extension.
#
# Usage: bash benches/python-overhead.sh   (builds the wheel into a throwaway
# venv, release profile; then `cargo bench --bench python_call`).
# Both sides give the best and the median batch, per call. Python: timeit,
# 15 repeats of a batch sized to >= 0.2 s. Rust: criterion's 15 samples,
# flat sampling (equal batches of about 0.2 s), read from
# target/criterion/python_call/*/new/sample.json.
set -euo pipefail
cd "$(dirname "$0")/.."

tmp=$(mktemp -d "${TMPDIR:-/tmp}/stickslip-python-overhead.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
unset STICKSLIP_MODELS  # the checkout's models only
python3 -m venv "$tmp/venv"
export PATH="$tmp/venv/bin:$PATH"  # maturin's Python shim runs `maturin` from PATH
py="$tmp/venv/bin/python"
echo "== building the wheel (pip install ./python) into a throwaway venv"
"$py" -m pip install -q numpy maturin
"$py" -m pip install -q --no-build-isolation ./python

echo "== Python (timeit)"
(cd "$tmp" && "$py" - > "$tmp/python.txt") <<'PY'
import timeit
import stickslip

m = stickslip.Model("paper")
r = m.simulate(W=5, Q0=70)
assert r.kind == "periodic" and r.structure == "P_{3_31 1_12 2_22 1_21 3_13 4_33}", r
calls = {
    "simulate": lambda: m.simulate(W=5, Q0=70),
    "history": lambda: r.history(),
    "simulate+history": lambda: m.simulate(W=5, Q0=70).history(),
    "models": lambda: stickslip.models(),
}
for name, call in calls.items():
    t = timeit.Timer(call)
    number, _ = t.autorange()
    times = sorted(x / number for x in t.repeat(repeat=15, number=number))
    print(name, times[0], times[len(times) // 2])
PY
cat "$tmp/python.txt"

echo "== Rust (cargo bench --bench python_call)"
cargo bench --bench python_call -- --output-format bencher | tee "$tmp/rust.txt"

"$py" - "$tmp/python.txt" target/criterion/python_call <<'PY'
import json
import statistics
import sys

py = {}
for line in open(sys.argv[1]):
    if line.strip():
        name, best, median = line.split()
        py[name] = (float(best), float(median))


def criterion(bench):
    d = json.load(open(f"{sys.argv[2]}/{bench}/new/sample.json"))
    per = [t * 1e-9 / n for t, n in zip(d["times"], d["iters"])]
    return min(per), statistics.median(per)


sim, hist = criterion("simulate_w5"), criterion("history_w5")
rust_of = {
    "simulate": sim,
    "history": hist,
    "simulate+history": (sim[0] + hist[0], sim[1] + hist[1]),
}
calls = {
    "simulate": "m.simulate(W=5, Q0=70)",
    "history": "r.history() (400 samples)",
    "simulate+history": "m.simulate(W=5, Q0=70).history()",
    "models": "stickslip.models()",
}


def fmt(s):
    return f"{s * 1e6:.1f} µs" if s < 1e-3 else f"{s * 1e3:.3f} ms"


print()
print("| call (Python) | Python best | Rust best (same work) | Python / Rust | overhead (best) | Python / Rust (medians) |")
print("|---|---:|---:|---:|---:|---:|")
for k, text in calls.items():
    (p, pm) = py[k]
    if k in rust_of:
        (r, rm) = rust_of[k]
        print(f"| `{text}` | {fmt(p)} | {fmt(r)} | {p / r:.3f} | {fmt(p - r)} | {pm / rm:.3f} |")
    else:
        print(f"| `{text}` | {fmt(p)} | — | — | {fmt(p)} | — |")
PY
