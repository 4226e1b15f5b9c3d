#!/usr/bin/env bash
# End to end on a real scheduler: starts a single-node Slurm (munged, slurmctld, slurmd as root,
# state in a temporary folder), runs samples/slurm/ssrcl-array.sbatch over a generated shot with
# 4 array tasks, and checks every output against a local `ssrcl trace`; then cancels a job
# mid-run, resubmits it, and checks that only the missing frames were computed; last, checks a
# mirror shot's outputs against each frame's exact reflections (independent truth).
#   test_slurm_array.sh SSRCL MAKE_SEQUENCE CHECK_MIRROR_SEQUENCE SBATCH_SCRIPT
# Exits 77 (skipped) where Slurm is not installed or cannot be started; KEEP=1 keeps the folder.
set -euo pipefail
ssrcl=$(realpath "$1") make_sequence=$(realpath "$2") check_mirror=$(realpath "$3") script=$(realpath "$4")
export PATH=$PATH:/usr/sbin:/sbin

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }

if [ "$(id -u)" -ne 0 ]; then
  sudo -n true 2>/dev/null || skip "starting slurmctld and slurmd needs root or passwordless sudo"
  exec sudo -n -E bash "$0" "$@"
fi
for tool in munged slurmctld slurmd sbatch squeue scancel sinfo; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (Debian: apt-get install slurmctld slurmd slurm-client munge)"
done

work=$(mktemp -d /tmp/ssrcl-slurm.XXXXXX)
chmod 755 "$work"
export SLURM_CONF=$work/slurm.conf
pids=()
cleanup() {
  set +e
  # Jobs first, so no job step outlives the daemons that track it.
  if [ -n "$(squeue -h -o %i 2>/dev/null)" ]; then
    scancel $(squeue -h -o %A | sort -u) 2>/dev/null
    for _ in $(seq 50); do [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  for pid in "${pids[@]}" $(cat "$work/munge/munged.pid" 2>/dev/null); do kill "$pid" 2>/dev/null; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null; done
  if [ "${KEEP:-0}" = 1 ]; then echo "kept $work"; else rm -rf "$work"; fi
}
trap cleanup EXIT
logs() { for f in "$work"/*.log "$work"/munge/*.log "$work"/logs/*.log; do [ -f "$f" ] && { echo "--- $f"; tail -20 "$f"; }; done; }

# A port nothing listens on (bash's /dev/tcp connects only when something does).
free_port() {
  local port
  while :; do
    port=$((20000 + RANDOM % 40000))
    (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null || { echo "$port"; return; }
  done
}

mkdir -p "$work"/{munge,state,spool,logs,reports}
chmod 700 "$work/munge"
head -c 1024 /dev/urandom >"$work/munge/munge.key"
chmod 400 "$work/munge/munge.key"
munged --force --socket="$work/munge/munge.sock" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed" ||
  { logs; skip "munged does not start here"; }

host=$(hostname -s)
cat >"$SLURM_CONF" <<CONF
ClusterName=ssrcltest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.sock
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1
ReturnToService=2
SlurmdParameters=config_overrides
KillWait=10
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

slurmctld -D -c -f "$SLURM_CONF" >"$work/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" >"$work/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 150); do
  [ "$(sinfo -h -n "$host" -o %T 2>/dev/null)" = idle ] && break
  sleep 0.2
done
[ "$(sinfo -h -n "$host" -o %T 2>/dev/null)" = idle ] || { logs; skip "slurmctld/slurmd did not come up here"; }
echo "Slurm up: node $host, $(nproc) CPUs"

export SSRCL=$ssrcl
# Submits the array job; prints the job id.
submit() {
  local reports=$1
  shift
  mkdir -p "$reports"
  SSRCL_REPORT_DIR=$reports sbatch --parsable -D "$work" -o "$work/logs/%A_%a.log" "$@" | cut -d';' -f1
}
wait_job() {
  for _ in $(seq 600); do [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return; sleep 0.2; done
  logs
  fail "job $1 did not finish in 2 minutes"
}
count() { grep -ho "\"status\": \"$1\"" "$2"/*.json | wc -l; }
no_temporaries() { [ -z "$(find "$1" -name '.*' -type f)" ] || fail "temporary files left in $1: $(find "$1" -name '.*')"; }
# Every frame of the pattern has an output identical to a local `ssrcl trace` of it.
matches_trace() {
  local frames=$1 out=$2 n=0
  shift 2
  for exr in $frames; do
    local stem
    stem=$(basename "$exr" .exr)
    [ -f "$out/$stem.refl.exr" ] || fail "$out/$stem.refl.exr is missing"
    "$ssrcl" trace "$exr" -o "$work/trace.exr" "$@" >/dev/null
    cmp -s "$out/$stem.refl.exr" "$work/trace.exr" || fail "$out/$stem.refl.exr differs from ssrcl trace"
    n=$((n + 1))
  done
  echo "$n outputs identical to ssrcl trace"
}

# 1. A shot of 8 frames in 4 array tasks; `--temporal 0`: each frame alone, as `ssrcl trace`.
"$make_sequence" "$work/shot" 8 64 36 0.3 >/dev/null
job=$(submit "$work/reports/1" --array=0-3 "$script" "$work/shot/shot.####.exr" "$work/out1/" --temporal 0)
wait_job "$job"
[ "$(ls "$work/reports/1" | wc -l)" -eq 4 ] || { logs; fail "expected a report from each of the 4 tasks"; }
[ "$(count done "$work/reports/1")" -eq 8 ] || { logs; fail "the 4 tasks did not compute the 8 frames once each"; }
matches_trace "$work/shot/shot.*.exr" "$work/out1"
no_temporaries "$work/out1"

# 2. Cancelled mid-run (one task at a time, slow frames), then resubmitted.
"$make_sequence" "$work/slow" 12 160 90 0.3 >/dev/null
slow=("$script" "$work/slow/shot.####.exr" "$work/out2/" --quality reference --spp 64 --temporal 0)
job=$(submit "$work/reports/2a" --array=0-3%1 "${slow[@]}")
for _ in $(seq 600); do
  compgen -G "$work/out2/*.exr" >/dev/null || [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
  sleep 0.1
done
scancel "$job"
wait_job "$job"
before=$(ls "$work/out2" 2>/dev/null | wc -l)
[ "$before" -gt 0 ] && [ "$before" -lt 12 ] || { logs; fail "cancelling left $before of 12 outputs: not mid-run"; }
no_temporaries "$work/out2"
inodes=$(stat -c '%n %i' "$work"/out2/*.exr)
echo "cancelled with $before of 12 frames done"

job=$(submit "$work/reports/2b" --array=0-3 "${slow[@]}")
wait_job "$job"
[ "$(count done "$work/reports/2b")" -eq $((12 - before)) ] || { logs; fail "the rerun did not compute exactly the $((12 - before)) missing frames"; }
[ "$(count skipped "$work/reports/2b")" -eq "$before" ] || fail "the rerun did not skip the $before frames done"
[ "$(stat -c '%n %i' $(echo "$inodes" | cut -d' ' -f1))" = "$inodes" ] || fail "the rerun rewrote finished frames"
matches_trace "$work/slow/shot.*.exr" "$work/out2" --quality reference --spp 64
no_temporaries "$work/out2"

# 3. A mirror shot (a camera orbiting 2 degrees a frame) in 2 array tasks: each output matches
# its own frame's exact reflections.
"$make_sequence" "$work/mirror" 4 160 90 >/dev/null
job=$(submit "$work/reports/3" --array=0-1 "$script" "$work/mirror/shot.####.exr" "$work/out3/" --edge-fade 0)
wait_job "$job"
"$check_mirror" "$work/out3" 4 160 90 || { logs; fail "the array job's outputs do not match the exact reflections"; }
echo "PASS"
