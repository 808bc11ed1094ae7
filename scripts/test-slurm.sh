#!/usr/bin/env bash
# End-to-end test of the Slurm scripts on a real Slurm, on this machine.
#
# Installs Slurm and MUNGE from Debian's packages (if missing), starts munged,
# slurmctld and slurmd on this one host with a private single-node
# configuration, submits scripts/slurm-submit.sh (a job array of map shards and
# a merge job that depends on it), waits for both, and compares the merged map
# byte for byte with a single-process `stickslip map` of the same grid. Then it
# cuts one shard file to half (as a task killed mid-run leaves it), requeues
# that array task with `scontrol requeue`, and checks that the task resumes the
# file (--resume) to the same bytes.
#
#   sudo scripts/test-slurm.sh        # as root; Debian or Ubuntu with apt
#
# Environment:
#   STICKSLIP           binary to test (default: build target/release/stickslip)
#   SLURM_TEST_DIR      state, config, logs and outputs (default: /var/tmp/stickslip-slurm-test;
#                       wiped at the start of each run)
#   SLURM_TEST_TIMEOUT  seconds to wait for the jobs (default: 300)
#   SLURM_TEST_X, SLURM_TEST_Y, SLURM_TEST_SHARDS  the grid and shard count
#                       (default: W=0.2:9:40, Q0=40:80:20, 4: 800 points, about a second of work)
#
# Exit status: 0 when the merged map equals the single run; non-zero on any
# failure. Only when the packages cannot be installed (no package registry)
# does it print "SKIP: <reason>" and exit 0.
#
# The daemons run on their own ports (16817/16818) with their own config
# (SLURM_CONF), so an existing Slurm on the machine is left alone; the daemons
# this script started (and a munged it had to start) are stopped on exit.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/.." && pwd)
BASE=${SLURM_TEST_DIR:-/var/tmp/stickslip-slurm-test}
TIMEOUT=${SLURM_TEST_TIMEOUT:-300}
GRID_X=${SLURM_TEST_X:-W=0.2:9:40}
GRID_Y=${SLURM_TEST_Y:-Q0=40:80:20}
NSHARDS=${SLURM_TEST_SHARDS:-4}
MODEL=paper
CTLD_PORT=16817
SLURMD_PORT=16818

t0=$(date +%s)
say() { printf '[test-slurm %4ss] %s\n' "$(($(date +%s) - t0))" "$*"; }
fail() {
    say "FAIL: $*"
    exit 1
}

if [ "$(id -u)" != 0 ]; then
    fail "must run as root (it installs packages and starts munged, slurmctld and slurmd)"
fi

# ---------------------------------------------------------------- packages
case ":$PATH:" in *:/usr/sbin:*) ;; *) PATH=$PATH:/usr/sbin:/sbin ;; esac
need_install=0
for c in munged munge slurmctld slurmd sbatch squeue sinfo scontrol; do
    command -v "$c" > /dev/null 2>&1 || need_install=1
done
if [ "$need_install" = 1 ]; then
    if ! command -v apt-get > /dev/null 2>&1; then
        echo "SKIP: no apt-get on this machine to install Slurm and MUNGE"
        exit 0
    fi
    say "installing slurm-wlm and munge from Debian's packages"
    export DEBIAN_FRONTEND=noninteractive
    if ! apt-get -q update > "/tmp/test-slurm-apt.log" 2>&1; then
        tail -n 20 /tmp/test-slurm-apt.log
        echo "SKIP: apt-get update failed (no package registry reachable), cannot install slurm-wlm and munge"
        exit 0
    fi
    if ! apt-get install -y -q --no-install-recommends -o DPkg::Lock::Timeout=300 \
        slurm-wlm slurmctld slurmd slurm-client munge >> /tmp/test-slurm-apt.log 2>&1; then
        tail -n 20 /tmp/test-slurm-apt.log
        echo "SKIP: apt-get install slurm-wlm munge failed (packages cannot be installed here)"
        exit 0
    fi
    for c in munged munge slurmctld slurmd sbatch squeue sinfo scontrol; do
        command -v "$c" > /dev/null 2>&1 || fail "installed the packages, but '$c' is still missing"
    done
fi
say "Slurm $(slurmd -V | awk '{print $2}'), MUNGE $(munged -V 2>&1 | awk '{print $1}' | sed 's/^munge-//')"

# ---------------------------------------------------------------- cleanup
# Every process of this test cluster (slurmctld, slurmd, slurmstepd, the jobs)
# carries SLURM_CONF=$BASE/slurm.conf in its environment: that is how leftovers
# of a run that was killed are found, and nothing else is touched.
marker="SLURM_CONF=$BASE/slurm.conf"
marked_pids() {
    local d p
    for d in /proc/[0-9]*; do
        p=${d#/proc/}
        if [ "$p" = $$ ] || [ "$p" = "$BASHPID" ]; then continue; fi
        grep -qzx -- "$marker" "$d/environ" 2> /dev/null && echo "$p"
    done
    return 0
}
alive() { # a pid that is running, not a zombie
    local st
    st=$(awk '{print $3}' "/proc/$1/stat" 2> /dev/null) || return 1
    [ -n "$st" ] && [ "$st" != Z ]
}
any_alive() {
    local p
    for p in "$@"; do alive "$p" && return 0; done
    return 1
}
stop_pids() { # TERM, up to 5 s, then KILL
    [ $# -gt 0 ] || return 0
    kill "$@" 2> /dev/null || true
    for _ in $(seq 50); do
        any_alive "$@" || return 0
        sleep 0.1
    done
    kill -9 "$@" 2> /dev/null || true
}
started=() # "pid name" of the daemons started here
slurm_env_ready=0
cleanup() {
    local rc=$?
    set +e
    if [ "$slurm_env_ready" = 1 ]; then
        scancel --quiet --full --user=root > /dev/null 2>&1
        for _ in $(seq 50); do
            [ -z "$(squeue -h -o %i 2> /dev/null)" ] && break
            sleep 0.2
        done
    fi
    local i entry pid name
    for ((i = ${#started[@]} - 1; i >= 0; i--)); do # the reverse order: slurmd, slurmctld, munged
        entry=${started[i]}
        pid=${entry%% *}
        name=${entry#* }
        if [ "$name" = munged ]; then
            # shellcheck disable=SC2046 # pids
            stop_pids $(marked_pids) # job processes outliving slurmd, if any
        fi
        if alive "$pid"; then
            stop_pids "$pid"
            say "stopped $name (pid $pid)"
        fi
    done
    exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

mkdir -p "$BASE"
stale=$(marked_pids)
if [ -n "$stale" ]; then
    say "stopping processes left by an earlier run of this test: $(tr '\n' ' ' <<< "$stale")"
    # shellcheck disable=SC2086
    stop_pids $stale
fi
if [ -f "$BASE/munged.pid" ]; then
    pid=$(cat "$BASE/munged.pid")
    if alive "$pid" && [ "$(cat "/proc/$pid/comm" 2> /dev/null)" = munged ]; then
        say "stopping munged left by an earlier run (pid $pid)"
        stop_pids "$pid"
    fi
    rm -f "$BASE/munged.pid"
fi
rm -rf "${BASE:?}"/{spool,state,log,out,single.csv,slurm.conf,cgroup.conf,slurmctld.pid,slurmd.pid}
mkdir -p "$BASE"/{spool,state,log,out}

# ---------------------------------------------------------------- munge
if munge -n 2> /dev/null | unmunge > /dev/null 2>&1; then
    say "munged is already running"
else
    if [ ! -s /etc/munge/munge.key ]; then
        say "creating /etc/munge/munge.key"
        mkdir -p /etc/munge
        if command -v mungekey > /dev/null 2>&1; then
            mungekey --create --keyfile=/etc/munge/munge.key
        else
            dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=1024 status=none
        fi
    fi
    # munged refuses keys, directories or sockets with loose permissions or the wrong owner.
    mkdir -p /run/munge /var/lib/munge /var/log/munge
    chown munge:munge /etc/munge /etc/munge/munge.key /run/munge /var/lib/munge /var/log/munge
    chmod 0700 /etc/munge /var/lib/munge /var/log/munge
    chmod 0600 /etc/munge/munge.key
    chmod 0755 /run/munge
    say "starting munged"
    rm -f /run/munge/munged.pid
    runuser -u munge -- munged --force || fail "munged did not start (see /var/log/munge/munged.log)"
    for _ in $(seq 50); do
        [ -s /run/munge/munged.pid ] && break
        sleep 0.1
    done
    munged_pid=$(cat /run/munge/munged.pid)
    started+=("$munged_pid munged")
    echo "$munged_pid" > "$BASE/munged.pid"
    munge -n | unmunge > /dev/null || fail "munge credentials do not verify"
fi

# ---------------------------------------------------------------- slurm.conf
host=$(hostname -s 2> /dev/null || uname -n)
cpus=$(nproc)
mem_mb=$(awk '/^MemTotal:/ {print int($2 / 1024 / 2)}' /proc/meminfo) # half: never "Low RealMemory"
export SLURM_CONF=$BASE/slurm.conf
cat > "$SLURM_CONF" << EOF
# Single-node test cluster written by scripts/test-slurm.sh (Slurm $(slurmd -V | awk '{print $2}')).
ClusterName=stickslip-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
# A requeued job waits cred_expire seconds (default 120) before it may start again.
AuthInfo=cred_expire=5
CredType=cred/munge
StateSaveLocation=$BASE/state
SlurmdSpoolDir=$BASE/spool
SlurmctldPidFile=$BASE/slurmctld.pid
SlurmdPidFile=$BASE/slurmd.pid
SlurmctldLogFile=$BASE/log/slurmctld.log
SlurmdLogFile=$BASE/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups (none usable in containers and sandboxes), no accounting.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
# Schedule often, so that a requeued job starts soon after its begin time.
SchedulerParameters=sched_interval=2,bf_interval=2
ReturnToService=2
# Keep finished jobs visible to scontrol for a while (there is no sacct without accounting).
MinJobAge=600
InactiveLimit=0
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=60
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF

# ---------------------------------------------------------------- daemons
slurm_logs() {
    local d f
    for d in slurmctld slurmd; do
        # The daemons log to their log file once they have read slurm.conf, to stderr before.
        for f in "$BASE/log/$d.log" "$BASE/log/$d.stderr"; do
            [ -s "$f" ] || continue
            echo "---- $f (last 40 lines)"
            tail -n 40 "$f"
            break
        done
    done
}
say "starting slurmctld (port $CTLD_PORT)"
slurmctld -D -c -i -f "$SLURM_CONF" > "$BASE/log/slurmctld.stderr" 2>&1 &
started+=("$! slurmctld")
echo "$!" > "$BASE/slurmctld.pid"
for _ in $(seq 100); do
    scontrol ping 2> /dev/null | grep -q 'is UP' && break
    kill -0 "${started[-1]%% *}" 2> /dev/null || { slurm_logs; fail "slurmctld exited"; }
    sleep 0.2
done
scontrol ping | grep -q 'is UP' || { slurm_logs; fail "slurmctld does not answer"; }
slurm_env_ready=1

say "starting slurmd (node $host, $cpus CPUs, port $SLURMD_PORT)"
slurmd -D -f "$SLURM_CONF" > "$BASE/log/slurmd.stderr" 2>&1 &
started+=("$! slurmd")
echo "$!" > "$BASE/slurmd.pid"
state=
for _ in $(seq 150); do
    state=$(sinfo -h -n "$host" -o %T 2> /dev/null | head -n 1)
    case $state in idle*) break ;; esac
    kill -0 "${started[-1]%% *}" 2> /dev/null || { slurm_logs; fail "slurmd exited"; }
    sleep 0.2
done
case $state in
    idle*) say "node $host is idle" ;;
    *) sinfo -N -l || true; scontrol show node "$host" || true; slurm_logs; fail "node $host is '$state', not idle" ;;
esac
sinfo

# ---------------------------------------------------------------- binary
if [ -z "${STICKSLIP:-}" ]; then
    say "building stickslip (cargo build --release)"
    (cd "$repo" && cargo build --release --quiet)
    STICKSLIP=$repo/target/release/stickslip
fi
[ -x "$STICKSLIP" ] || fail "no executable $STICKSLIP"
STICKSLIP=$(cd "$(dirname "$STICKSLIP")" && pwd)/$(basename "$STICKSLIP")
say "binary: $STICKSLIP"

# ---------------------------------------------------------------- submit
out=$BASE/out
say "submitting $NSHARDS shards of $MODEL $GRID_X x $GRID_Y and the merge"
submitted=$(cd "$BASE" && STICKSLIP=$STICKSLIP MODEL=$MODEL X=$GRID_X Y=$GRID_Y SHARDS=$NSHARDS OUTDIR=$out PLOT=$out/map.png \
    "$here/slurm-submit.sh") || { slurm_logs; fail "slurm-submit.sh failed"; }
echo "$submitted"
array_id=$(sed -n 's/^ARRAY_JOB_ID=//p' <<< "$submitted")
merge_id=$(sed -n 's/^MERGE_JOB_ID=//p' <<< "$submitted")
merged=$(sed -n 's/^MAP=//p' <<< "$submitted")
if [ -z "$array_id" ] || [ -z "$merge_id" ] || [ -z "$merged" ]; then
    fail "slurm-submit.sh printed no job ids"
fi

show_jobs() {
    local f
    echo "---- squeue"
    squeue || true
    echo "---- scontrol show job $array_id"
    scontrol show job "$array_id" || true
    echo "---- scontrol show job $merge_id"
    scontrol show job "$merge_id" || true
    for f in "$out"/logs/*; do
        [ -f "$f" ] || continue
        echo "---- $f"
        cat "$f"
    done
    slurm_logs
}

# wait_jobs JOBSPEC: poll squeue (pending and running jobs) until none of JOBSPEC
# (comma-separated job ids or array tasks) is left, at most $TIMEOUT seconds.
wait_jobs() {
    local deadline last='' queue now
    deadline=$(($(date +%s) + TIMEOUT))
    while :; do
        queue=$(squeue -h -j "$1" -o '%i %T' 2> /dev/null | sort || true)
        [ -n "$queue" ] || return 0
        now=$(tr '\n' ' ' <<< "$queue")
        [ "$now" = "$last" ] || say "queue: $now"
        last=$now
        if [ "$(date +%s)" -ge "$deadline" ]; then
            show_jobs
            fail "jobs not finished after ${TIMEOUT}s"
        fi
        sleep 1
    done
}

# not_completed JOBSPEC...: "id state exit restarts" of every job (or array task)
# that did not end COMPLETED with exit code 0:0; also prints a line per job
# to $BASE/log/states (one-line scontrol records).
not_completed() {
    local j
    for j in "$@"; do scontrol -o show job "$j" 2> /dev/null || echo "JobId=$j JobState=UNKNOWN"; done > "$BASE/log/states"
    awk '{ id = ""; st = ""; ex = ""; rs = "";
           for (i = 1; i <= NF; i++) {
               if ($i ~ /^JobId=/) id = substr($i, 7);
               if ($i ~ /^ArrayTaskId=/) id = id "[task " substr($i, 13) "]";
               if ($i ~ /^JobState=/) st = substr($i, 10);
               if ($i ~ /^ExitCode=/) ex = substr($i, 10);
               if ($i ~ /^Restarts=/) rs = substr($i, 10) }
           if (st != "COMPLETED" || ex != "0:0") print id, st, ex, "restarts=" rs }' "$BASE/log/states"
}

# ---------------------------------------------------------------- wait
wait_jobs "$array_id,$merge_id"
bad=$(not_completed "$array_id" "$merge_id")
ntasks=$(grep -c "ArrayJobId=$array_id " "$BASE/log/states" || true)
if [ -n "$bad" ] || [ "$ntasks" != "$NSHARDS" ]; then
    show_jobs
    echo "---- not completed (id state exit):"
    echo "$bad"
    fail "the array ($ntasks of $NSHARDS tasks seen) or the merge did not complete"
fi
say "all $NSHARDS array tasks and the merge completed"
for ((k = 0; k < NSHARDS; k++)); do
    [ -s "$out/shard-$k.csv" ] || fail "shard $k wrote nothing ($out/shard-$k.csv)"
done
[ -f "$merged" ] || { show_jobs; fail "no merged map $merged"; }
[ -s "$out/map.png" ] || { show_jobs; fail "the merge job drew no figure $out/map.png"; }

# ---------------------------------------------------------------- compare
say "single-process run of the same grid"
single=$BASE/single.csv
"$STICKSLIP" map --model "$MODEL" --x "$GRID_X" --y "$GRID_Y" --out "$single" > "$BASE/log/single.log" 2>&1 ||
    { cat "$BASE/log/single.log"; fail "single-process stickslip map failed"; }
if ! cmp "$merged" "$single"; then
    diff "$merged" "$single" | head -n 20 || true
    fail "merged Slurm map differs from the single-process run"
fi
say "merged map from $NSHARDS Slurm array tasks equals the single run ($(wc -l < "$single") lines, $(wc -c < "$single") bytes)"

# ---------------------------------------------------------------- requeue
# A task killed half-way and requeued resumes its shard: cut one shard file to
# its first half (as a task killed mid-run leaves it), requeue that finished
# array task, and check that it completes the file to the same bytes.
k=$((NSHARDS > 1 ? 1 : 0))
shard=$out/shard-$k.csv
cp "$shard" "$BASE/shard-$k.full"
lines=$(wc -l < "$shard")
keep=$(((lines + 1) / 2))
head -n "$keep" "$BASE/shard-$k.full" > "$shard"
say "requeue: shard $k cut to $keep of $lines lines; scontrol requeue ${array_id}_$k"
scontrol requeue "${array_id}_$k" || { show_jobs; fail "scontrol requeue ${array_id}_$k failed"; }
sleep 1
wait_jobs "${array_id}_$k"
bad=$(not_completed "${array_id}_$k")
if [ -n "$bad" ] || ! grep -q "Restarts=1 " "$BASE/log/states"; then
    show_jobs
    echo "---- ${array_id}_$k: $bad"
    cat "$BASE/log/states"
    fail "the requeued task ${array_id}_$k did not complete once more"
fi
if ! cmp "$shard" "$BASE/shard-$k.full"; then
    diff "$shard" "$BASE/shard-$k.full" | head -n 20 || true
    fail "the requeued task's resumed shard differs from the first run's"
fi
# The task's log (appended to on requeue) must show a second run that found
# points already done (the CLI reports "N already done"): a rerun that simply
# recomputed everything would give the same bytes too.
log=$out/logs/map-${array_id}_$k.out
resumed=$(awk '/restart 1/ { again = 1 } again && /already done/' "$log")
if [ -z "$resumed" ]; then
    say "note: $log does not say how many points the requeued run found done"
elif ! grep -Eq '(^|[^0-9])[1-9][0-9]* already done' <<< "$resumed"; then
    cat "$log"
    fail "the requeued task recomputed its shard instead of resuming it"
else
    say "requeued task: $(grep -Eo '[0-9]+ computed now, [0-9]+ already done' <<< "$resumed" | head -n 1)"
fi
say "requeued task resumed shard $k to the same bytes"
say "PASS: Slurm array + merge equals the single run; a requeued task resumes its shard (${SECONDS}s)"
