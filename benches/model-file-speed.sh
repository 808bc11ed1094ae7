#!/usr/bin/env bash
# The main job with the model compiled in (`--model paper`) against the same
# job on the model file loaded at run time (`--model-file models/paper.ssm`:
# read, checked, compiled to machine code, then the sweep), side by side in
# one run: the two commands alternate, N times each, and the medians, the
# minima and their ratios are printed. Also `describe`, which is nearly all
# load. Needs the release CLI (`cargo build --release`).
#
#   bash benches/model-file-speed.sh [N]      # N = 30 by default
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-30}
bin=target/release/stickslip
[ -x "$bin" ] || { echo "no $bin: cargo build --release first" >&2; exit 1; }

python3 - "$bin" "$n" <<'PY'
import statistics
import subprocess
import sys
import time

bin, n = sys.argv[1], int(sys.argv[2])
jobs = {
    "main job (sweep W=0.2:9:200, Q0=70)": ["sweep", "--param", "W=0.2:9:200", "--set", "Q0=70"],
    "describe": ["describe"],
}
for name, args in jobs.items():
    runs = {"--model paper": [], "--model-file models/paper.ssm": []}
    outputs = {}
    for _ in range(n):
        for how in runs:
            cmd = [bin, *args, *how.split()]
            t = time.perf_counter()
            out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
            runs[how].append(time.perf_counter() - t)
            outputs[how] = out
    a, b = runs.values()
    same = "same output" if len(set(outputs.values())) == 1 else "OUTPUTS DIFFER"
    print(f"{name}, {n} runs each, alternating ({same}):")
    for how, ts in runs.items():
        print(f"  {how:<32} median {1e3 * statistics.median(ts):7.1f} ms   min {1e3 * min(ts):7.1f} ms")
    print(f"  ratio loaded/compiled            median {statistics.median(b) / statistics.median(a):.2f}"
          f"      min {min(b) / min(a):.2f}")
PY
