#!/usr/bin/env bash
# voxrg compare on a real Slurm cluster of one node: starts munged,
# slurmctld and slurmd on localhost from a configuration written into a
# temporary folder (Debian's slurm-wlm and munge, which scripts/setup.sh
# installs), submits scripts/compare-array.sbatch as a 4-task array (each
# task a shard of a tiny case file's 2 cases x 2 candidates, all four
# filling one shared reference cache at once) and its --merge job with
# --dependency=afterok, waits for them, and checks the results: the merged
# metrics.csv and metrics.json (but timings) equal those of one process
# the test runs itself, which takes every reference frame from the cache
# the shards left, without a warning. The daemons are stopped however the
# test ends.
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
pids=() array="" merge=""
stop() {
    [ -n "$array$merge" ] && scancel $array $merge 2>/dev/null && sleep 1 # the jobs first, while slurmd runs
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
# (30 s: on a loaded 2-core machine, beside the browser test, 10 were once too few)
wait_for 30 test -S "$tmp/munge/socket" || fail "munged did not start in 30 s"

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

# a tiny run: 2 cases x 2 candidates (raw.ini and thesis.ini on a world
# of radius 2) against reference.ini at 2 samples a frame, as 4 shards
shared=$out/shared
mkdir -p "$shared" "$out/graphs"
for g in raw thesis reference; do
    sed 's/^radius      = 13$/radius      = 2/' "$src/graphs/$g.ini" >"$out/graphs/$g.ini"
done
grep -q '^radius      = 2$' "$out/graphs/raw.ini" || fail "graphs/raw.ini's world radius is no longer 13: change the sed"
printf '[case walk]\ncamera = %s\nstart = 10\nframes = 3\nwarmup = 1\nsize = 32x18\n\n[case evening]\nframes = 2\nwarmup = 0\nsize = 24x16\nscene.time_of_day = 17.5\n' \
    "$src/graphs/paths/walk.path" >"$out/tiny.cases"
run=("$out/graphs/raw.ini" "$out/graphs/thesis.ini" --reference "$out/graphs/reference.ini" --ref-set converge.samples_per_frame=2
    --cases "$out/tiny.cases")
script=$src/scripts/compare-array.sbatch
array=$(VOXRG=$voxrg sbatch --parsable --chdir="$out" --output="$out/task-%a.out" --array=0-3 "$script" 4 "$shared" "${run[@]}") ||
    fail "sbatch of the array job"
merge=$(VOXRG=$voxrg sbatch --parsable --chdir="$out" --output="$out/merge.out" --dependency="afterok:$array" "$script" --merge 4 "$shared") ||
    fail "sbatch of the merge job"
state() { scontrol show job "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | head -1; }
finished() { case $(state) in JobState=COMPLETED | JobState=FAILED | JobState=CANCELLED | JobState=TIMEOUT) return 0 ;; esac; return 1; }
wait_for 60 finished || fail "the jobs did not finish in 60 s: $(squeue 2>&1)"
[ "$(state)" = JobState=COMPLETED ] || fail "the merge job ended $(state); $(cat "$out"/task-*.out "$out/merge.out" 2>/dev/null | tail -30)"
for i in 0 1 2 3; do
    [ -f "$shared/shard-$i/shard.txt" ] || fail "task $i wrote no shard.txt: $(tail -5 "$out/task-$i.out")"
    grep -q "warning: the reference cache" "$out/task-$i.out" && fail "task $i warned: $(grep warning "$out/task-$i.out")"
done
grep -q '^merged 4 shards' "$out/merge.out" || fail "the merge job's output: $(tail -5 "$out/merge.out")"
# one process, the same run: its metrics equal the merged ones, but for
# timings; and the four writers left whole cache entries, so it takes
# every reference frame (3 + 2) from them, without a warning
"$voxrg" compare "${run[@]}" --cache "$shared/cache" --out "$out/single" >"$out/single.out" 2>&1 ||
    fail "compare in one process: $(tail -5 "$out/single.out")"
cmp "$out/single/metrics.csv" "$shared/out/metrics.csv" || fail "the merged metrics.csv differs from one process's"
python3 -c '
import json, sys
def without_timing(metrics):  # what runs of the same work differ in
    for case in metrics["cases"]:
        case["reference"].pop("frames_from_cache")
        for c in case["candidates"]:
            c["summary"].pop("gpu_ms_mean"), c["summary"].pop("gpu_ms_p95")
            c["passes"] = [p["name"] for p in c["passes"]]
    return metrics
single, merged = (without_timing(json.load(open(f))) for f in sys.argv[1:])
if single != merged:
    sys.exit("one process:\n%s\nmerged:\n%s" % (json.dumps(single)[:1500], json.dumps(merged)[:1500]))
' "$out/single/metrics.json" "$shared/out/metrics.json" || fail "the merged metrics.json differs from one process's"
[ "$(grep -o '"frames_from_cache": [0-9]*' "$out/single/metrics.json" | tr '\n' ' ')" = '"frames_from_cache": 3 "frames_from_cache": 2 ' ] ||
    fail "after the jobs: $(grep frames_from_cache "$out/single/metrics.json")"
grep -q "warning: the reference cache" "$out/single.out" && fail "after the jobs: $(grep warning "$out/single.out")"
ls -A "$shared/cache" | grep -q '^\.' && fail "temporary files left in the cache: $(ls -A "$shared/cache")"
echo "slurm: ok (array job $array, merge job $merge)"
