#!/usr/bin/env bash
# voxrg compare on a real Slurm cluster of one node: starts munged,
# slurmctld and slurmd on localhost from a configuration written into a
# temporary folder (Debian's slurm-wlm and munge, which scripts/setup.sh
# installs), submits scripts/compare-array.sbatch as a 4-task array (each
# task compares one candidate graph against the reference, all four
# filling one shared reference cache at once) and its --check job with
# --dependency=afterok, waits for them, and checks the results: every
# task's metrics.json, the check job's list, and a cache whose entries a
# run afterwards takes, all of them, without a warning. The daemons are
# stopped however the test ends.
# Exits 77 (skipped) only where Slurm cannot start: not root (slurmd
# starts jobs as their user), or the packages are missing.
# Usage: slurm_cluster.sh VOXRG SOURCE_DIR OUT_DIR
set -u
voxrg=$(realpath "$1") src=$(realpath "$2") out=$3
skip() { echo "skipped: $*"; exit 77; }
[ "$(id -u)" -eq 0 ] || skip "Slurm's daemons run as root here (slurmd starts each job as its user); run as root"
for b in munged mungekey slurmctld slurmd sbatch scontrol sinfo; do
    command -v "$b" >/dev/null || skip "$b is missing: install slurm-wlm and munge (scripts/setup.sh)"
done

rm -rf "$out"
mkdir -p "$out"
out=$(realpath "$out")
tmp=$(mktemp -d /tmp/voxrg-slurm.XXXXXX)
pids=() array="" check=""
stop() {
    [ -n "$array$check" ] && scancel $array $check 2>/dev/null && sleep 1 # the jobs first, while slurmd runs
    for pid in "${pids[@]}"; do
        kill "$pid" 2>/dev/null
    done
    for pid in "${pids[@]}"; do
        wait "$pid" 2>/dev/null
    done
    rm -rf "$tmp"
}
trap stop EXIT
trap 'exit 1' INT TERM # ctest's timeout: stop the daemons all the same
fail() {
    echo "FAIL: $*"
    for log in "$tmp"/*.log; do
        [ -f "$log" ] && { echo "--- $log"; tail -15 "$log"; }
    done
    exit 1
}
# waits up to $1 seconds for the command after it to succeed
wait_for() {
    local limit=$1
    shift
    for _ in $(seq $((limit * 5))); do
        "$@" >/dev/null 2>&1 && return 0
        sleep 0.2
    done
    return 1
}

# munge, its key and socket in the temporary folder
mkdir -m 700 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key" || fail "mungekey could not make a key"
munged --foreground --force --socket="$tmp/munge/socket" --key-file="$tmp/munge/munge.key" --pid-file="$tmp/munge/munged.pid" \
    --seed-file="$tmp/munge/seed" --log-file="$tmp/munged.log" 2>"$tmp/munged.stderr.log" &
pids+=($!)
wait_for 10 test -S "$tmp/munge/socket" || fail "munged did not start"

# two free ports for the daemons: tests may run side by side
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
mkdir "$tmp/state" "$tmp/spool"
export SLURM_CONF=$tmp/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=voxrg-test
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -c -f "$SLURM_CONF" 2>"$tmp/slurmctld.stderr.log" &
pids+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" 2>"$tmp/slurmd.stderr.log" &
pids+=($!)
idle() { sinfo -h -N -o %t | grep -qx idle; }
wait_for 30 idle || fail "the node did not come up idle: $(sinfo -N 2>&1)"

# four candidates: the test wall at four exposures of its sky (time of
# day is the scene's, so it stays); one reference, the wall itself
shared=$out/shared
mkdir -p "$shared" "$out/graphs"
cp "$src/tests/graphs/blocks_wall.ini" "$out/graphs/reference.ini"
: >"$out/candidates.txt"
for i in 0 1 2 3; do
    cp "$src/tests/graphs/blocks_wall.ini" "$out/graphs/c$i.ini"
    echo "$out/graphs/c$i.ini" >>"$out/candidates.txt"
done
script=$src/scripts/compare-array.sbatch
options=(--camera "$src/graphs/paths/walk.path" --size 32x18 --frames 4 --warmup 0)
array=$(VOXRG=$voxrg sbatch --parsable --chdir="$out" --output="$out/task-%a.out" --array=0-3 "$script" \
    "$out/candidates.txt" "$out/graphs/reference.ini" "$shared" "${options[@]}") || fail "sbatch of the array job"
check=$(sbatch --parsable --chdir="$out" --output="$out/check.out" --dependency="afterok:$array" "$script" --check \
    "$out/candidates.txt" "$out/graphs/reference.ini" "$shared") || fail "sbatch of the check job"
state() { scontrol show job "$check" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | head -1; }
finished() { case $(state) in JobState=COMPLETED | JobState=FAILED | JobState=CANCELLED | JobState=TIMEOUT) return 0 ;; esac; return 1; }
wait_for 60 finished || fail "the jobs did not finish in 60 s: $(squeue 2>&1)"
[ "$(state)" = JobState=COMPLETED ] || fail "the check job ended $(state); $(cat "$out"/task-*.out "$out/check.out" 2>/dev/null | tail -30)"
for i in 0 1 2 3; do
    [ -f "$shared/out/$i/metrics.json" ] || fail "task $i wrote no metrics.json: $(tail -5 "$out/task-$i.out")"
    grep -q warning "$out/task-$i.out" && fail "task $i warned: $(grep warning "$out/task-$i.out")"
done
[ "$(grep -c '^candidate [0-3] ' "$out/check.out")" -eq 4 ] || fail "the check job's list: $(cat "$out/check.out")"
# the four writers left whole entries: a run now takes every frame from them
"$voxrg" compare "$out/graphs/c0.ini" --reference "$out/graphs/reference.ini" --cache "$shared/cache" --out "$out/after" "${options[@]}" \
    >"$out/after.out" 2>&1 || fail "compare after the jobs: $(tail -5 "$out/after.out")"
grep -q '"frames_from_cache": 4' "$out/after/metrics.json" || fail "after the jobs: $(grep frames_from_cache "$out/after/metrics.json")"
grep -q warning "$out/after.out" && fail "after the jobs: $(grep warning "$out/after.out")"
ls -A "$shared/cache" | grep -q '^\.' && fail "temporary files left in the cache: $(ls -A "$shared/cache")"
echo "slurm: ok (array job $array, check job $check)"
