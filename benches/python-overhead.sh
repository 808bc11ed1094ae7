#!/usr/bin/env bash
# The Python package's overhead: `simulate` at W = 5, Q0 = 70 (paper model,
# from rest) called from Python against the same work in Rust
# (benches/python_call.rs), in one run; also `Motion.history()`, both
# together, and a trivial call (`stickslip.models()`): the fixed cost of
# crossing into the extension.
#
# Usage: bash benches/python-overhead.sh   (builds the wheel into a throwaway
# venv, release profile; then `cargo bench --bench python_call`).
# Python: timeit, best of 7 repeats of a batch sized to >= 0.2 s, per call.
# Rust: criterion's estimate per iteration (bencher format).
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
    best = min(t.repeat(repeat=7, number=number)) / number
    print(name, best)
PY
cat "$tmp/python.txt"

echo "== Rust (cargo bench --bench python_call)"
cargo bench --bench python_call -- --output-format bencher | tee "$tmp/rust.txt"

"$py" - "$tmp/python.txt" "$tmp/rust.txt" <<'PY'
import re
import sys

py = dict((l.split()[0], float(l.split()[1])) for l in open(sys.argv[1]) if l.strip())
rust = {}
for line in open(sys.argv[2]):
    m = re.match(r"test python_call/(\S+)\s+\.\.\. bench:\s+([\d,]+) ns/iter", line)
    if m:
        rust[m.group(1)] = float(m.group(2).replace(",", "")) * 1e-9
rust_of = {
    "simulate": rust["simulate_w5"],
    "history": rust["history_w5"],
    "simulate+history": rust["simulate_w5"] + rust["history_w5"],
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
print("| call (Python) | Python | Rust (same work) | Python / Rust | overhead |")
print("|---|---:|---:|---:|---:|")
for k, text in calls.items():
    p = py[k]
    if k in rust_of:
        r = rust_of[k]
        print(f"| `{text}` | {fmt(p)} | {fmt(r)} | {p / r:.3f} | {fmt(p - r)} |")
    else:
        print(f"| `{text}` | {fmt(p)} | — | — | {fmt(p)} |")
PY
