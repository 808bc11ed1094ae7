#!/usr/bin/env bash
# One shard of a `stickslip map`, as a task of a Slurm job array.
#
# Each array task k of n computes the 16 x 16-point tiles of the grid whose number (row by row) is k mod n into
# $OUTDIR/shard-k.csv. `scripts/slurm-merge.sh` then joins the shards into
# $OUTDIR/map.csv, byte-identical to a single `stickslip map` of the whole
# grid. `scripts/slurm-submit.sh` submits both (the merge waits for the whole
# array with --dependency=afterok) and prints the job ids; use it rather than
# calling sbatch on this file by hand.
#
# Usage on a cluster (run from the repository, on a filesystem that every
# compute node sees, so that the binary and OUTDIR are reachable):
#
#   cargo build --release
#   SHARDS=16 X=W=0.2:9:400 Y=Q0=40:80:200 OUTDIR=$PWD/map-run \
#       scripts/slurm-submit.sh --partition=compute --account=myproject --time=01:00:00
#
# or by hand (the array must be 0..SHARDS-1):
#
#   sbatch --array=0-15 --export=ALL,SHARDS=16,OUTDIR=$PWD/map-run scripts/slurm-map.sh
#
# Parameters (environment variables, exported into the job by sbatch):
#   STICKSLIP  the binary (default: $SLURM_SUBMIT_DIR/target/release/stickslip,
#              else `stickslip` on PATH)
#   MODEL      model name (default: paper)
#   X, Y       the grid axes, NAME=from:to:count (default: W=3:5:21, Q0=40:80:11)
#   SET        the other parameters, passed as --set (e.g. d=0.1,c=30; default: none)
#   OUTDIR     where shard-K.csv go (default: $SLURM_SUBMIT_DIR/stickslip-map)
#   SHARDS     number of shards n (default: $SLURM_ARRAY_TASK_COUNT)
#
# Threads: `stickslip map` uses rayon; RAYON_NUM_THREADS is set to the CPUs
# Slurm gave the task (--cpus-per-task), so raise --cpus-per-task to use more
# cores per shard.
#
# Requeue and resume: the shard file is written incrementally and the task
# always runs with --resume, so a task that is requeued (node failure,
# preemption, `scontrol requeue`) or resubmitted after being killed continues
# where it stopped: points already in shard-K.csv are neither lost nor
# computed twice. To redo only failed tasks of an array, resubmit with the
# same SHARDS and e.g. --array=3,7 (SHARDS must then be given explicitly).
#
# Partitions, accounts, QOS and time limits are site-specific: uncomment and
# edit the lines below, or pass them on the sbatch / slurm-submit.sh command
# line (command-line options override #SBATCH lines), or set SBATCH_PARTITION,
# SBATCH_ACCOUNT, SBATCH_TIMELIMIT in the environment.
#
#SBATCH --job-name=stickslip-map
#SBATCH --array=0-3
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --requeue
#SBATCH --open-mode=append
#SBATCH --output=slurm-%x-%A_%a.out
##SBATCH --partition=compute
##SBATCH --account=myproject
##SBATCH --qos=normal
##SBATCH --time=01:00:00
##SBATCH --mem-per-cpu=1G
set -euo pipefail

: "${SLURM_ARRAY_TASK_ID:?this script runs as a task of a Slurm job array (sbatch --array=0-N)}"
submit_dir=${SLURM_SUBMIT_DIR:-$PWD}
if [ -z "${STICKSLIP:-}" ]; then
    if [ -x "$submit_dir/target/release/stickslip" ]; then
        STICKSLIP=$submit_dir/target/release/stickslip
    else
        STICKSLIP=stickslip
    fi
fi
MODEL=${MODEL:-paper}
X=${X:-W=3:5:21}
Y=${Y:-Q0=40:80:11}
set_args=()
[ -z "${SET:-}" ] || set_args=(--set "$SET")
OUTDIR=${OUTDIR:-$submit_dir/stickslip-map}

if [ -z "${SHARDS:-}" ]; then
    SHARDS=${SLURM_ARRAY_TASK_COUNT:?SLURM_ARRAY_TASK_COUNT is not set; set SHARDS}
    # Without SHARDS the array has to be exactly 0..n-1, or shards would overlap or be missed.
    if [ "${SLURM_ARRAY_TASK_MIN:-0}" != 0 ] || [ "${SLURM_ARRAY_TASK_MAX:-}" != $((SHARDS - 1)) ]; then
        echo "error: array ${SLURM_ARRAY_TASK_MIN:-?}-${SLURM_ARRAY_TASK_MAX:-?} is not 0-$((SHARDS - 1)); set SHARDS to the total number of shards" >&2
        exit 2
    fi
fi
k=$SLURM_ARRAY_TASK_ID
if [ "$k" -ge "$SHARDS" ]; then
    echo "error: array task $k is outside 0..$((SHARDS - 1)) (SHARDS=$SHARDS)" >&2
    exit 2
fi

export RAYON_NUM_THREADS=${RAYON_NUM_THREADS:-${SLURM_CPUS_PER_TASK:-1}}
mkdir -p "$OUTDIR"
out=$OUTDIR/shard-$k.csv
echo "stickslip-map: job ${SLURM_ARRAY_JOB_ID:-?}_$k on $(hostname -s): shard $k/$SHARDS of $MODEL $X x $Y${SET:+ ($SET)} -> $out" \
    "(restart ${SLURM_RESTART_COUNT:-0}, $RAYON_NUM_THREADS threads)"
"$STICKSLIP" map --model "$MODEL" --x "$X" --y "$Y" ${set_args[@]+"${set_args[@]}"} --shard "$k/$SHARDS" --out "$out" --resume
echo "stickslip-map: shard $k/$SHARDS done"
