#!/usr/bin/env bash
# The main job timed side by side with the SciPy baseline, in one run
# (issue 11, item 6; benches/README.md, "SciPy baseline").
#
#   benches/sweep-vs-scipy.sh            # 20 stickslip runs, one Python sweep
#   RUNS=50 benches/sweep-vs-scipy.sh
#   PYTHON=/path/to/python benches/sweep-vs-scipy.sh   # skip the venv
#   SCIPY_ARGS="--W 3,5" RUNS=3 benches/sweep-vs-scipy.sh   # a quick try of the script (no ratio to quote)
#
# 1. builds the release CLI;
# 2. times `stickslip sweep --model paper --param W=0.2:9:200 --set Q0=70` as a
#    process, RUNS times (best and median, wall clock, and CPU time);
# 3. times `python benches/scipy/sweep.py` once (the same 200 W values to their
#    steady states with solve_ivp / DOP853 and event location);
# 4. prints both times and the ratio, then checks the Python results against
#    `stickslip sweep ... --json`;
# 5. prints the machine's load before and after (the machine may be shared).
#
# Without $PYTHON, a venv is made in target/scipy-venv from
# benches/scipy/requirements.txt (the package registry is the only network use).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
runs="${RUNS:-20}"
out="target/sweep-vs-scipy"
mkdir -p "$out"

load() { echo "load ($1): $(cut -d' ' -f1-3 /proc/loadavg) (1/5/15 min) on $(nproc) CPUs"; }

if [[ -z "${PYTHON:-}" ]]; then
    venv="target/scipy-venv"
    if [[ ! -x "$venv/bin/python" ]]; then
        echo "making $venv (numpy, scipy from benches/scipy/requirements.txt)" >&2
        python3 -m venv "$venv"
        "$venv/bin/pip" install --quiet -r benches/scipy/requirements.txt
    fi
    PYTHON="$venv/bin/python"
fi
"$PYTHON" -c 'import numpy, scipy, sys; print(f"python {sys.version.split()[0]}, numpy {numpy.__version__}, scipy {scipy.__version__}")'

cargo build --release --quiet
bin="target/release/stickslip"
job=(sweep --model paper --param W=0.2:9:200 --set Q0=70)

# Seconds, with nanoseconds, of the wall clock.
now() { date +%s.%N; }
# CPU seconds (user + system) of this shell's finished children so far
# (the second line of `times`: "0m1.234s 0m0.056s").
# `times` runs in this shell (a command substitution would fork and count nothing).
child_cpu() {
    times > "$out/times.txt"
    tail -1 "$out/times.txt" | awk '{ split($0, f, /[ ms]+/); print f[1] * 60 + f[2] + f[3] * 60 + f[4] }'
}

load "before"
echo "stickslip: ${job[*]} ($runs runs as a process, output to /dev/null)"
"$bin" "${job[@]}" > /dev/null   # warm the page cache once
walls=()
for ((i = 0; i < runs; i++)); do
    t0=$(now)
    "$bin" "${job[@]}" > /dev/null
    t1=$(now)
    walls+=("$(echo "$t1 - $t0" | bc -l)")
done
# CPU time in a loop of its own: nothing but the runs between the two
# readings (the wall-clock loop's `date` and `bc` would add ~6 ms a run).
child_cpu > "$out/cpu0.txt"
cpu0=$(cat "$out/cpu0.txt")
for ((i = 0; i < runs; i++)); do
    "$bin" "${job[@]}" > /dev/null
done
child_cpu > "$out/cpu1.txt"
cpu1=$(cat "$out/cpu1.txt")
stats() { printf '%s\n' "$@" | sort -g | awk '{ a[NR] = $1 } END { m = (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2; printf "%.4f %.4f %.4f\n", a[1], m, a[NR] }'; }
read -r ss_best ss_median ss_worst < <(stats "${walls[@]}")
ss_cpu_mean=$(echo "($cpu1 - $cpu0) / $runs" | bc -l)
printf 'stickslip: best %.1f ms, median %.1f ms, worst %.1f ms wall; mean CPU (user + sys) %.1f ms\n' \
    "$(echo "$ss_best * 1000" | bc -l)" "$(echo "$ss_median * 1000" | bc -l)" \
    "$(echo "$ss_worst * 1000" | bc -l)" "$(echo "$ss_cpu_mean * 1000" | bc -l)"
"$bin" "${job[@]}" --json > "$out/stickslip.json"

echo "scipy: benches/scipy/sweep.py (once: 200 W values, DOP853 rtol 1e-10, events, steady state)"
t0=$(now)
# shellcheck disable=SC2086  # SCIPY_ARGS is a list of words
/usr/bin/time -f "%U %S" -o "$out/time.txt" "$PYTHON" benches/scipy/sweep.py --out "$out/scipy.json" ${SCIPY_ARGS:-}
t1=$(now)
py_wall=$(echo "$t1 - $t0" | bc -l)
py_cpu=$(awk '{ print $1 + $2 }' "$out/time.txt")
printf 'scipy: %.2f s wall (CPU %.2f s) as a process, interpreter start and imports included\n' "$py_wall" "$py_cpu"
load "after"

printf 'ratio (scipy / stickslip), wall: %.0fx against the median, %.0fx against the best; CPU: %.0fx\n' \
    "$(echo "$py_wall / $ss_median" | bc -l)" "$(echo "$py_wall / $ss_best" | bc -l)" \
    "$(echo "$py_cpu / $ss_cpu_mean" | bc -l)"

echo "check: the SciPy steady states against stickslip sweep --json"
"$PYTHON" benches/scipy/sweep.py --result "$out/scipy.json" --check "$out/stickslip.json"
