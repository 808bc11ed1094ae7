#!/usr/bin/env bash
# The eight `curves` runs the guide's "Regime maps" chapter quotes, each run
# alone and timed (wall), with its counts: curves, codimension-two points,
# ends that are neither on the box's edge nor at a codimension-two
# point (a corrector failure, a crawl, the point limit), and located
# transitions whose curve could not be traced (`failed_starts`).
#
#   benches/curves-runs.sh            # all eight (pl4 takes most of the time)
#   benches/curves-runs.sh s8box      # one of them, by name
#   EXTRA="--probes 4" benches/curves-runs.sh fig11   # with more options
#   EXTRA=--no-edges benches/curves-runs.sh          # without the box edges' sweeps
#                                                    # (on by default)
#   BIN=/tmp/old/stickslip OUT=/tmp/old-runs benches/curves-runs.sh  # another build
#
# The JSON of each run is kept in target/curves-runs/NAME.json (or OUT).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="${OUT:-target/curves-runs}"
mkdir -p "$out"
if [ -z "${BIN:-}" ]; then cargo build --release --quiet; fi
bin="${BIN:-target/release/stickslip}"

run() {
    local name=$1
    shift
    if [ -n "${ONLY:-}" ] && [ "$ONLY" != "$name" ]; then return; fi
    local s e
    s=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$bin" curves "$@" ${EXTRA:-} --json >"$out/$name.json"
    e=$(date +%s.%N)
    python3 - "$out/$name.json" "$name" "$(echo "$e - $s" | bc)" <<'PY'
import json, sys
path, name, t = sys.argv[1:]
d = json.load(open(path))
ends = [e for c in d["curves"] for e in (c["from"], c["to"]) if e]
bad = [e for e in ends if e["end"] not in ("box_edge", "codim2")]
print(f"{name}: {len(d['curves'])} curves, {len(d['codim2'])} codim-2 points, "
      f"{len(bad)}/{len(ends)} other ends, {len(d['failed_starts'])} failed starts, "
      f"{float(t):.1f} s")
PY
}

ONLY="${1:-}"
run fig11 --model paper --x W=0.2:8 --y Q0=0:180 --seed Q0=70
run cascade --model paper --x W=6.6:7.3 --y Q0=30:48
run shaw --model coulomb --x W=0.3:1.2 --y Q0=0.5:2 --set V=0,d=0,mus=0.45,muk=0.3
run s8box --model stribeck8 --x W=2.3:2.6 --y Q0=1:3
run s8full --model stribeck8 --x W=0.5:3 --y Q0=1:12
run mm40 --model paper --x W=5:8 --y Q0=20:60 --max-mappings 40
run pl4 --model stribeck::pl4 --x W=0.5:3 --y Q0=1:12
# The box of tests/curve_stick_end.rs: sticks whose exits turn tangential.
run stickend --model paper --x W=2.6:2.9 --y Q0=185:215 --seed Q0=200
