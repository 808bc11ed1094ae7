#!/usr/bin/env bash
# Submit a sharded `stickslip map` to Slurm: a job array of SHARDS tasks
# (scripts/slurm-map.sh, one shard each) and a merge job
# (scripts/slurm-merge.sh) that starts only when every task has succeeded
# (--dependency=afterok) and is cancelled if one fails.
#
#   SHARDS=16 MODEL=paper X=W=0.2:9:400 Y=Q0=40:80:200 OUTDIR=$PWD/map-run \
#       scripts/slurm-submit.sh [sbatch options for both jobs, e.g. --partition=P --account=A --time=1:00:00]
#
# Environment: SHARDS (default 4), STICKSLIP, MODEL, X, Y, SET, OUTDIR, MAP, PLOT as
# documented in slurm-map.sh and slurm-merge.sh; paths are made absolute here.
# MAP_SBATCH_ARGS / MERGE_SBATCH_ARGS: extra options for one of the two jobs
# only (e.g. MAP_SBATCH_ARGS="--cpus-per-task=8").
#
# Prints, one per line:
#   ARRAY_JOB_ID=<id>
#   MERGE_JOB_ID=<id>
#   MAP=<the merged file, written when the merge job completes>
# Watch with `squeue -j <ids>`; logs go to $OUTDIR/logs/.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/.." && pwd)

SHARDS=${SHARDS:-4}
case $SHARDS in
    '' | *[!0-9]* | 0) echo "error: SHARDS must be a positive integer, not '$SHARDS'" >&2; exit 2 ;;
esac
abspath() { case $1 in /*) printf '%s\n' "$1" ;; *) printf '%s\n' "$PWD/$1" ;; esac; }
if [ -z "${STICKSLIP:-}" ]; then
    if [ -x "$repo/target/release/stickslip" ]; then
        STICKSLIP=$repo/target/release/stickslip
    else
        STICKSLIP=$(command -v stickslip || true)
        [ -n "$STICKSLIP" ] || { echo "error: no stickslip binary: run 'cargo build --release' or set STICKSLIP" >&2; exit 2; }
    fi
fi
case $STICKSLIP in */*) STICKSLIP=$(abspath "$STICKSLIP") ;; esac
MODEL=${MODEL:-paper}
X=${X:-W=3:5:21}
Y=${Y:-Q0=40:80:11}
OUTDIR=$(abspath "${OUTDIR:-stickslip-map}")
[ -z "${PLOT:-}" ] || PLOT=$(abspath "$PLOT")
MAP=$(abspath "${MAP:-$OUTDIR/map.csv}")
export STICKSLIP MODEL X Y SET OUTDIR SHARDS MAP PLOT
mkdir -p "$OUTDIR/logs"

# shellcheck disable=SC2086 # MAP_SBATCH_ARGS / MERGE_SBATCH_ARGS are word lists
array_id=$(sbatch --parsable --export=ALL --array="0-$((SHARDS - 1))" \
    --output="$OUTDIR/logs/map-%A_%a.out" "$@" ${MAP_SBATCH_ARGS:-} "$here/slurm-map.sh")
array_id=${array_id%%;*} # --parsable prints "id" or "id;cluster"
# shellcheck disable=SC2086
merge_id=$(sbatch --parsable --export=ALL --dependency="afterok:$array_id" --kill-on-invalid-dep=yes \
    --output="$OUTDIR/logs/merge-%j.out" "$@" ${MERGE_SBATCH_ARGS:-} "$here/slurm-merge.sh")
merge_id=${merge_id%%;*}

echo "ARRAY_JOB_ID=$array_id"
echo "MERGE_JOB_ID=$merge_id"
echo "MAP=$MAP"
