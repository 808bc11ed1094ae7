#!/usr/bin/env bash
# Merge the shards of a `stickslip map` job array (scripts/slurm-map.sh) into
# one map: $OUTDIR/map.csv, byte-identical to a single `stickslip map` run
# of the whole grid, and optionally a figure.
#
# `scripts/slurm-submit.sh` submits this with --dependency=afterok:<array job>,
# so it runs only once every shard has finished. It also runs outside Slurm:
#
#   SHARDS=16 OUTDIR=$PWD/map-run scripts/slurm-merge.sh
#
# Parameters (environment variables): STICKSLIP, OUTDIR as in slurm-map.sh;
#   SHARDS  number of shards (required: shard-0.csv .. shard-(SHARDS-1).csv
#           must all be there)
#   MAP     the merged file (default: $OUTDIR/map.csv)
#   PLOT    if set, also draw the map to this file (e.g. $OUTDIR/map.png)
#
# Site-specific lines (see slurm-map.sh):
#SBATCH --job-name=stickslip-merge
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --output=slurm-%x-%j.out
##SBATCH --partition=compute
##SBATCH --account=myproject
##SBATCH --time=00:10:00
set -euo pipefail

submit_dir=${SLURM_SUBMIT_DIR:-$PWD}
if [ -z "${STICKSLIP:-}" ]; then
    if [ -x "$submit_dir/target/release/stickslip" ]; then
        STICKSLIP=$submit_dir/target/release/stickslip
    else
        STICKSLIP=stickslip
    fi
fi
OUTDIR=${OUTDIR:-$submit_dir/stickslip-map}
: "${SHARDS:?set SHARDS to the number of shards}"
MAP=${MAP:-$OUTDIR/map.csv}

shards=()
missing=0
for ((k = 0; k < SHARDS; k++)); do
    f=$OUTDIR/shard-$k.csv
    if [ ! -f "$f" ]; then
        echo "error: missing $f" >&2
        missing=1
    fi
    shards+=("$f")
done
[ "$missing" = 0 ] || exit 1

plot=()
[ -z "${PLOT:-}" ] || plot=(--plot "$PLOT")
echo "stickslip-merge: ${#shards[@]} shards in $OUTDIR -> $MAP${PLOT:+ and $PLOT}"
"$STICKSLIP" merge "${shards[@]}" --out "$MAP" ${plot[@]+"${plot[@]}"}
echo "stickslip-merge: done"
