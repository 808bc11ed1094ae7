#!/usr/bin/env bash
# The 200 x 200 basin grid of the paper model in the window with three
# stable motions (W = 3.94826, Q0 = 70), timed at 1 and 2 threads (issue 13,
# item 6; benches/README.md, "Basins (issue 13)").
#
#   benches/basins-speed.sh              # 200 x 200 grid + 1000 random starts, 1 and 2 threads
#
# 1. builds the release CLI;
# 2. times `stickslip basins --set W=3.94826,Q0=70 --x x=0.99:1.005:200
#    --y v=1.335:1.36:200 --samples 1000` at RAYON_NUM_THREADS=1 and 2:
#    wall, CPU (user + sys) and starts per second per core of CPU;
# 3. checks that the two files are byte-identical;
# 4. prints the machine's load before and after (the machine may be shared).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="target/basins-speed"
mkdir -p "$out"
load() { echo "load ($1): $(cut -d' ' -f1-3 /proc/loadavg) (1/5/15 min) on $(nproc) CPUs"; }

cargo build --release --quiet
bin="target/release/stickslip"

# Prints "wall cpu starts" (seconds, seconds, count).
timed() {
    local threads=$1 file=$2
    rm -f "$file"
    local t0 t1
    t0=$(date +%s.%N)
    /usr/bin/time -f "%U %S" -o "$out/time.txt" env RAYON_NUM_THREADS="$threads" \
        "$bin" basins --model paper --set W=3.94826,Q0=70 --x x=0.99:1.005:200 \
        --y v=1.335:1.36:200 --samples 1000 --out "$file" > "$file.txt"
    t1=$(date +%s.%N)
    local cpu starts
    cpu=$(awk '{ print $1 + $2 }' "$out/time.txt")
    starts=$(($(wc -l < "$file") - 2))
    echo "$(echo "$t1 - $t0" | bc -l) $cpu $starts"
}

report() {
    printf '%-28s wall %7.2f s  CPU %7.2f s  %8.0f starts/s per core  (%d starts)\n' \
        "$1" "$2" "$3" "$(echo "$4 / $3" | bc -l)" "$4"
}

load "before"
read -r w1 c1 n1 < <(timed 1 "$out/t1.csv")
report "200 x 200 + 1000, 1 thread" "$w1" "$c1" "$n1"
read -r w2 c2 n2 < <(timed 2 "$out/t2.csv")
report "200 x 200 + 1000, 2 threads" "$w2" "$c2" "$n2"
cmp "$out/t1.csv" "$out/t2.csv" && echo "1 and 2 threads wrote byte-identical files"
cat "$out/t2.csv.txt"
load "after"
