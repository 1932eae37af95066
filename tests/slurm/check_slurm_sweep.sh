#!/usr/bin/env bash
# A speed sweep run as a Slurm job array on a one-node cluster that this script starts itself,
# merged with `gaitopt sweep-merge`, equals the same sweep run in one process.
#
# Usage: check_slurm_sweep.sh SOURCE_DIR BUILD_DIR
#
# Starts munged, slurmctld and slurmd (Debian's munge and slurm-wlm) as the current user on
# localhost, from a slurm.conf generated in a temporary folder (one node, select/cons_tres,
# proctrack/linuxproc, no cgroups, no accounting, free ports); submits scripts/slurm_sweep.sh
# as an array of SHARDS tasks over SPEEDS; waits for it; checks every task COMPLETED with exit
# code 0 (scontrol); merges the shard folders with sweep-merge; and compares with
# `gaitopt sweep --jobs SHARDS` in one process (the shard i of N is the chain i of --jobs N):
# sweep.csv byte for byte without its wall_time_s column, every per-speed file byte for byte
# except summary.json, compared without its wall-time members. Every daemon it started is
# stopped on exit, failure included. Exit 0 when equal, 1 otherwise.
set -euo pipefail

if [ "$#" -ne 2 ]; then
  sed -n '2,15p' "$0" >&2
  exit 2
fi
SOURCE="$(cd "$1" && pwd)"
BUILD="$(cd "$2" && pwd)"
GAITOPT="$BUILD/gaitopt"
SPEEDS="0.2:0.5:0.1"
SHARDS=2
WAIT_S=90

tmp="$(mktemp -d -t gaitopt-slurm.XXXXXX)"
chmod 755 "$tmp"  # munged wants its socket reachable by every user
job=""

fail() {
  echo "check_slurm_sweep: FAIL: $*" >&2
  for log in "$tmp"/*.log "$tmp"/submit/results/*.log; do
    [ -f "$log" ] && { echo "--- $log" >&2; tail -n 15 "$log" >&2; }
  done
  exit 1
}

stop_daemons() {
  # The job first (its tasks run under slurmd), then the daemons in reverse order of start,
  # each by the process id it wrote.
  if [ -n "$job" ]; then
    scancel "$job" 2>/dev/null || true
  fi
  local name pid
  for name in slurmd slurmctld munged; do
    pid="$(cat "$tmp/$name.pid" 2>/dev/null || true)"
    if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
      kill "$pid"
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -0 "$pid" 2>/dev/null && kill -9 "$pid"
    fi
  done
  rm -rf "$tmp"
}
trap stop_daemons EXIT

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# --- munge: a fresh key and its own socket, so that no system munged is needed or disturbed.
head -c 1024 /dev/urandom >"$tmp/munge.key"
chmod 600 "$tmp/munge.key"
munged --force --socket="$tmp/munge.socket" --key-file="$tmp/munge.key" \
  --pid-file="$tmp/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed" ||
  fail "munged exits $?"

# --- slurm.conf: the node as slurmd detects it (slurmd -C), so that it is not drained.
node="$(hostname -s)"
node_line="$(slurmd -C | head -n 1)"
case "$node_line" in
  "NodeName=$node "*) ;;
  *) fail "slurmd -C printed '$node_line', expected NodeName=$node ..." ;;
esac
mkdir -p "$tmp/state" "$tmp/spool"
cat >"$tmp/slurm.conf" <<EOF
ClusterName=gaitopt-test
SlurmctldHost=$node
SlurmUser=$(id -un)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
$node_line State=UNKNOWN
PartitionName=gaitopt Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$tmp/slurm.conf"

slurmctld -f "$SLURM_CONF" || fail "slurmctld exits $?"
slurmd -f "$SLURM_CONF" || fail "slurmd exits $?"
for _ in $(seq 100); do
  state="$(sinfo -h -n "$node" -o %t 2>/dev/null || true)"
  [ "$state" = idle ] && break
  sleep 0.2
done
[ "$state" = idle ] || fail "node $node is '$state' after 20 s, not idle"

# --- the array job, submitted as a user would: from a folder holding build/, configs/, results/.
mkdir -p "$tmp/submit/results"
ln -s "$BUILD" "$tmp/submit/build"
ln -s "$SOURCE/configs" "$tmp/submit/configs"
job="$(cd "$tmp/submit" && sbatch --parsable --array="0-$((SHARDS - 1))" \
  --export="ALL,SPEEDS=$SPEEDS" "$SOURCE/scripts/slurm_sweep.sh")" || fail "sbatch exits $?"
[[ "$job" =~ ^[0-9]+$ ]] || fail "sbatch printed '$job', not a job id"

# The one-process reference, while the array runs; from the same folder at the same depth as
# the shards, since gait.yaml names its robot file relative to itself.
(cd "$tmp/submit" && build/gaitopt sweep --config configs/default.yaml --speeds "$SPEEDS" \
  --jobs "$SHARDS" --quiet --out results/sweep_one >/dev/null 2>&1) ||
  fail "the one-process sweep exits $?"

for _ in $(seq $((WAIT_S * 2))); do
  queued="$(squeue -h -j "$job" -o %i)" || fail "squeue exits $?"
  [ -z "$queued" ] && break
  sleep 0.5
done
[ -z "$queued" ] || fail "job $job still queued after $WAIT_S s: $queued"

states="$(scontrol -o show job "$job")" || fail "scontrol show job exits $?"
completed="$(grep -c 'JobState=COMPLETED .* ExitCode=0:0' <<<"$states" || true)"
if [ "$completed" != "$SHARDS" ]; then
  seen="$(grep -o 'JobState=[A-Z_]*\|ExitCode=[0-9:]*' <<<"$states" | tr '\n' ' ')"
  fail "$completed of $SHARDS array tasks COMPLETED with exit code 0: $seen"
fi

shard_dirs=()
for ((i = 0; i < SHARDS; ++i)); do shard_dirs+=("$tmp/submit/results/sweep_shard_$i"); done
"$GAITOPT" sweep-merge --out "$tmp/merged" "${shard_dirs[@]}" >/dev/null ||
  fail "sweep-merge exits $?"

# --- the comparison: bytes, but for the wall times.
without_wall_time() {  # sweep.csv without its wall_time_s column (found by name)
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_time_s") w = i; if (!w) exit 1 }
           { out = ""; sep = ""
             for (i = 1; i <= NF; ++i) if (i != w) { out = out sep $i; sep = "," }
             print out }' "$1"
}
without_wall_time "$tmp/submit/results/sweep_one/sweep.csv" >"$tmp/one.csv" ||
  fail "one-process sweep.csv has no wall_time_s"
without_wall_time "$tmp/merged/sweep.csv" >"$tmp/merged.csv" ||
  fail "merged sweep.csv has no wall_time_s"
rows="$(($(wc -l <"$tmp/one.csv") - 1))"
[ "$rows" -ge 4 ] || fail "the one-process sweep has $rows rows"
cmp "$tmp/one.csv" "$tmp/merged.csv" || fail "merged sweep.csv differs from the one-process one"

compared=0
for speed_dir in "$tmp"/submit/results/sweep_one/v*/; do
  name="$(basename "$speed_dir")"
  shard=""
  for dir in "${shard_dirs[@]}"; do [ -d "$dir/$name" ] && shard="$dir/$name"; done
  [ -n "$shard" ] || fail "no shard folder holds $name"
  for file in "$speed_dir"*; do
    base="$(basename "$file")"
    if [ "$base" = summary.json ]; then
      python3 - "$file" "$shard/$base" <<'PY' || fail "$name/summary.json differs"
import json, sys
def drop(x):
    if isinstance(x, dict):
        return {k: drop(v) for k, v in x.items() if "wall_time" not in k}
    return [drop(v) for v in x] if isinstance(x, list) else x
a, b = (drop(json.load(open(p))) for p in sys.argv[1:])
sys.exit(0 if a == b else 1)
PY
    else
      cmp "$file" "$shard/$base" || fail "$name/$base differs"
    fi
    compared=$((compared + 1))
  done
done
echo "check_slurm_sweep: job $job, $SHARDS array tasks COMPLETED; merged sweep.csv ($rows speeds)" \
  "and $compared per-speed files equal to the one-process sweep --jobs $SHARDS"
