#!/usr/bin/env bash
# Redraw every figure the README and the guide show, through the CLI (and
# the Python package for the Python chapter's figure), into
# docs/guide/src/figures/.
#
#   bash scripts/figures.sh              # all of them (a few minutes, release build)
#   QUICK=1 bash scripts/figures.sh      # the fast ones, into a temporary folder removed at the end (CI)
#   OUT=/tmp/figs bash scripts/figures.sh   # somewhere else
#   STICKSLIP=/path/to/stickslip ...     # a given binary instead of building one
#
# The Python figure needs `import stickslip` to work in `python3` with
# matplotlib and pandas (`pip install "./python[examples]"`); without them it
# is skipped with a note.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=${QUICK:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [[ -n "$quick" ]]; then
    out=${OUT:-$tmp/figures}
else
    out=${OUT:-docs/guide/src/figures}
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
if [[ -z "${STICKSLIP:-}" ]]; then
    cargo build --release -q
    STICKSLIP=$PWD/target/release/stickslip
fi
s() { "$STICKSLIP" "$@" > /dev/null; }
figure() {
    local name=$1
    shift
    local start=$SECONDS
    "$@"
    [[ -s "$out/$name" ]] || { echo "error: $out/$name was not written" >&2; exit 1; }
    echo "  $name ($((SECONDS - start)) s)"
}
echo "figures into $out"
# Periodic motions.
figure orbit_w3.7.svg s orbit --model paper --structure "P_{3_31 0_11 3_13 4_33}" \
    --set W=3.7,Q0=70 --plot "$out/orbit_w3.7.svg"
# One-parameter studies: the main job, as a bifurcation diagram and as the
# frequency response; a period doubling; Shaw's pitchfork; Neimark–Sacker.
figure sweep_q70.png s sweep --model paper --param W=0.2:9:200 --set Q0=70 --plot "$out/sweep_q70.png"
figure frc_q70.png s sweep --model paper --param W=0.2:9:200 --set Q0=70 --plot "$out/frc_q70.png" --view frc
figure sweep_pd.png s sweep --model paper --param W=10.7:10.95:26 --set Q0=100,mu3=3 --plot "$out/sweep_pd.png"
figure sweep_shaw.png s sweep --model coulomb --param W=0.33:0.42:10 \
    --set V=0,d=0,mus=0.45,muk=0.3,Q0=1.5 --plot "$out/sweep_shaw.png"
figure sweep_ns.png s sweep --model paper --param W=10.3:11.3:51 --set Q0=100,mu3=4.4 --plot "$out/sweep_ns.png"
figure sweep_kinds.png s sweep --model paper --param W=9.2:11.3:43 --set Q0=80,mu3=4.4 --plot "$out/sweep_kinds.png"
# Self-excited oscillations: the belt's cycles and steady sliding, and their basins.
figure belt_law.png s sweep --model-file examples/belt.ssm --param vd=0.2:3:29 \
    --plot "$out/belt_law.png"
figure belt_frc.png s sweep --model-file examples/belt.ssm --scene pl16 --param vd=0.2:3:29 \
    --view frc --plot "$out/belt_frc.png"
figure belt_map.png s map --model-file examples/belt.ssm --scene pl16 --x vd=0.2:3:57 \
    --y zeta=0.01:0.1:37 --out "$tmp/belt_map.csv" --plot "$out/belt_map.png"
figure belt_basins.png s basins --model-file examples/belt.ssm --scene pl16 --set vd=1.4 \
    --x x=-1.5:2.5:161 --y v=-1:3:161 --out "$tmp/belt_basins.csv" --plot "$out/belt_basins.png"
# Smooth friction: the measured trade.
figure trade_stribeck.png s trade --model stribeck --plot "$out/trade_stribeck.png"
if [[ -n "$quick" ]]; then
    # The slower commands on small grids: they must keep working.
    figure map_small.png s map --model paper --x W=0.2:8:12 --y Q0=0:180:8 \
        --out "$tmp/map.csv" --plot "$out/map_small.png"
    figure regimes_small.png s curves --model paper --x W=3.5:3.8 --y Q0=65:75 \
        --count 12 --spread 0 --no-edges --plot "$out/regimes_small.png"
    figure basins_small.png s basins --model paper --set W=3.94826,Q0=70 --x x=0.99:1.005:20 \
        --y v=1.335:1.36:20 --samples 100 --out "$tmp/basins.csv" --plot "$out/basins_small.png"
    figure orbit_diagram_small.png s orbit-diagram --model stribeck8 --param W=1.8:2.45:12 \
        --set Q0=3 --transient 50 --periods 20 --lyapunov 50 --plot "$out/orbit_diagram_small.png"
    echo "quick subset done"
    exit 0
fi
# Regime maps: the grid, a window's curves, Fig. 11 from curves.
figure map_paper.png s map --model paper --x W=0.2:8:80 --y Q0=0:180:60 --method simulation \
    --out "$tmp/map.csv" --plot "$out/map_paper.png"
figure regimes_window.png s curves --model paper --x W=3:4.5 --y Q0=60:80 --count 24 --spread 1 \
    --at Q0=65,75 --plot "$out/regimes_window.png"
figure regimes_paper.png s curves --model paper --x W=0.2:8 --y Q0=0:180 --seed Q0=70 \
    --plot "$out/regimes_paper.png"
# Chaos and basins.
figure orbit_diagram.png s orbit-diagram --model stribeck8 --param W=1.8:2.45:130 --set Q0=3 \
    --transient 300 --periods 60 --lyapunov 300 --plot "$out/orbit_diagram.png"
figure basins_window.png s basins --model paper --set W=3.94826,Q0=70 --x x=0.99:1.005:200 \
    --y v=1.335:1.36:200 --samples 1000 --out "$tmp/basins.csv" --plot "$out/basins_window.png"
# Python: the package's ten-line example.
if python3 -c "import stickslip, matplotlib, pandas" 2> /dev/null; then
    (cd "$tmp" && mkdir -p docs/guide/src/figures \
        && python3 "$OLDPWD/examples/readme.py" > /dev/null \
        && cp docs/guide/src/figures/python_example.png "$out/python_example.png")
    echo "  python_example.png"
else
    echo "  python_example.png skipped: python3 cannot import stickslip, matplotlib and pandas" \
        "(pip install \"./python[examples]\")"
fi
echo "done"
