#!/usr/bin/env bash
# The map by continuation timed side by side with the map by simulation, in
# one run (issue 12, item 3; benches/README.md, "Map by continuation").
#
#   benches/map-speed.sh                 # 400 x 400 continuation (1 and 2 threads), 100 x 100 both methods
#   OLD400=1 benches/map-speed.sh        # also the 400 x 400 simulation map at 2 threads (~1-2 min)
#   CHECK=1 benches/map-speed.sh         # also the 100 x 100 check of guarantee 1 (tests/map_continuation.rs, release)
#
# 1. builds the release CLI;
# 2. times `stickslip map --model paper --x W=0.2:8:400 --y Q0=0:180:400`
#    (--method continuation, the default) at RAYON_NUM_THREADS=1 and 2:
#    wall, CPU (user + sys) and points per second per core of CPU;
# 3. times the 100 x 100 map (W=0.2:8:100, Q0=0:180:100) with both methods at
#    RAYON_NUM_THREADS=1 and prints the ratio measured in this run;
# 4. diffs the two 100 x 100 classifications: points where the continuation
#    map misses a motion of the simulation map (must be none), points where it
#    lists more (coexistence; proven by the CHECK test), status differences;
# 5. prints the machine's load before and after (the machine may be shared).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="target/map-speed"
mkdir -p "$out"
load() { echo "load ($1): $(cut -d' ' -f1-3 /proc/loadavg) (1/5/15 min) on $(nproc) CPUs"; }

cargo build --release --quiet
bin="target/release/stickslip"

# Runs `map` with the given thread count, method and grid side; prints
# "wall cpu points" (seconds, seconds, count) on stdout.
timed_map() {
    local threads=$1 method=$2 x=$3 y=$4 file=$5
    rm -f "$file"
    local t0 t1
    t0=$(date +%s.%N)
    /usr/bin/time -f "%U %S" -o "$out/time.txt" env RAYON_NUM_THREADS="$threads" \
        "$bin" map --model paper --x "$x" --y "$y" --method "$method" --out "$file" > /dev/null
    t1=$(date +%s.%N)
    local cpu
    cpu=$(awk '{ print $1 + $2 }' "$out/time.txt")
    local points
    points=$(($(wc -l < "$file") - 2))
    echo "$(echo "$t1 - $t0" | bc -l) $cpu $points"
}

report() {
    local label=$1 wall=$2 cpu=$3 points=$4
    printf '%-44s wall %7.2f s  CPU %7.2f s  %8.0f points/s per core  (%d points)\n' \
        "$label" "$wall" "$cpu" "$(echo "$points / $cpu" | bc -l)" "$points"
}

load "before"
X400="W=0.2:8:400"; Y400="Q0=0:180:400"
X100="W=0.2:8:100"; Y100="Q0=0:180:100"
read -r c1w c1c c1n < <(timed_map 1 continuation "$X400" "$Y400" "$out/c400-t1.csv")
report "continuation 400 x 400, 1 thread" "$c1w" "$c1c" "$c1n"
read -r c2w c2c c2n < <(timed_map 2 continuation "$X400" "$Y400" "$out/c400-t2.csv")
report "continuation 400 x 400, 2 threads" "$c2w" "$c2c" "$c2n"
cmp "$out/c400-t1.csv" "$out/c400-t2.csv" && echo "400 x 400: 1 and 2 threads wrote byte-identical files"
read -r n1w n1c n1n < <(timed_map 1 continuation "$X100" "$Y100" "$out/c100.csv")
report "continuation 100 x 100, 1 thread" "$n1w" "$n1c" "$n1n"
read -r s1w s1c s1n < <(timed_map 1 simulation "$X100" "$Y100" "$out/s100.csv")
report "simulation 100 x 100, 1 thread" "$s1w" "$s1c" "$s1n"
if [[ -n "${OLD400:-}" ]]; then
    read -r s2w s2c s2n < <(timed_map 2 simulation "$X400" "$Y400" "$out/s400-t2.csv")
    report "simulation 400 x 400, 2 threads" "$s2w" "$s2c" "$s2n"
    printf 'ratio 400 x 400 at 2 threads (simulation / continuation): wall %.2f, CPU %.2f\n' \
        "$(echo "$s2w / $c2w" | bc -l)" "$(echo "$s2c / $c2c" | bc -l)"
fi
printf 'ratio 100 x 100 at 1 thread (simulation / continuation): CPU %.2f\n' "$(echo "$s1c / $n1c" | bc -l)"
printf 'points/s per core: continuation 400 x 400 (1 thread) %.0f, simulation 100 x 100 %.0f: ratio %.2f\n' \
    "$(echo "$c1n / $c1c" | bc -l)" "$(echo "$s1n / $s1c" | bc -l)" \
    "$(echo "($c1n / $c1c) / ($s1n / $s1c)" | bc -l)"
load "after"

# The classifications, point by point (motions as sets).
python3 - "$out/s100.csv" "$out/c100.csv" <<'PY'
import csv, sys
def load(path):
    rows = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("index"):
                continue
            r = next(csv.reader([line]))
            rows[int(r[0])] = (r[3], set(m for m in r[4].split(";") if m))
    return rows
old, new = load(sys.argv[1]), load(sys.argv[2])
missing = [i for i in old if not old[i][1] <= new[i][1]]
extra = [i for i in old if old[i][1] < new[i][1]]
status = [i for i in old if old[i][0] != new[i][0]]
for i in missing[:20]:
    print(f"MISSING at {i}: simulation {sorted(old[i][1])}, continuation {sorted(new[i][1])}")
for i in extra:
    print(f"more at {i}: simulation {sorted(old[i][1])}, continuation {sorted(new[i][1])}")
for i in status[:20]:
    print(f"status at {i}: simulation `{old[i][0]}`, continuation `{new[i][0]}`")
print(f"100 x 100: {len(old)} points, {len(missing)} miss a simulated motion, "
      f"{len(extra)} list more (coexistence), {len(status)} status differences")
sys.exit(1 if missing else 0)
PY

if [[ -n "${CHECK:-}" ]]; then
    STICKSLIP_CHECK_GRID=100 cargo test --release --test map_continuation -- --nocapture 2>&1 | tail -15
fi
