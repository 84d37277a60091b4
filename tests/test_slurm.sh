#!/usr/bin/env bash
# Slurm in the suite (issue 59): a real single-node Slurm on localhost runs the
# shipped job-array script over a small study, and the merged rows equal the
# same study run locally, row for row.
#
#   1. munged, slurmctld and slurmd (Debian 12's munge and slurm-wlm 22.05)
#      start from a temporary folder: their own key, socket, slurm.conf (one
#      node, the machine's hostname at 127.0.0.1, free ports, no cgroups, no
#      accounting), state, spool and logs; nothing under /etc or /var is used.
#   2. cases/studies/slurm_sweep.sh is submitted as it ships (sbatch
#      --array=0-2, one `fourbar sweep --shard I/3` per task) over
#      tests/studies/tiny.ini (6 points), and waited for; every task must
#      end COMPLETED with exit code 0.
#   3. `fourbar merge` of the shards equals `fourbar sweep` of the same study
#      in one local process: points.csv byte for byte, points.jsonl line for
#      line.
#   4. The comparison fails when a shard's rows are lost or duplicated in the
#      merge's input (copies of the Slurm shards with one row removed, one
#      row repeated in another shard, one shard removed).
# Every wait is bounded (*_WAIT_S deadlines, every Slurm client under
# `timeout`: the test ends within about 9 minutes whatever happens); the
# daemons are stopped (TERM, then KILL) and the folder removed on any exit.
# Skipped (exit 77, with the reason) only when the daemons cannot start;
# under CI=true that fails instead.
# Usage: test_slurm.sh PATH_TO_FOURBAR. Prints "N passed, N failed".
set -u
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
here=$(cd "$(dirname "$0")" && pwd)
study=$here/studies/tiny.ini
script=$here/../cases/studies/slurm_sweep.sh
shards=3

# bounds of each wait [s]: each ends as soon as its condition holds; sized
# for the sanitizer build on a loaded 2-core machine (measured on an idle
# one: the node idle after 2 s, the array done after 5 s)
DAEMON_WAIT_S=90   # munged's socket, then the node idle in sinfo
JOB_WAIT_S=400     # the array's tasks gone from squeue
CLIENT_TIMEOUT_S=20  # one sbatch, squeue, sinfo, scontrol or scancel call
STOP_WAIT_S=20     # a daemon gone after TERM, before KILL

T=$(mktemp -d "${TMPDIR:-/tmp}/fourbar-slurm-XXXXXX")
pids=()
job=""
passed=0; failed=0
ok() { if eval "$1"; then passed=$((passed+1)); else failed=$((failed+1)); echo "FAIL: $2"; fi; }

# TERM to pid $1, a bounded wait, KILL
stop() {
  kill -TERM "$1" 2>/dev/null || return 0
  for _ in $(seq 1 $((STOP_WAIT_S * 10))); do kill -0 "$1" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$1" 2>/dev/null
  wait "$1" 2>/dev/null
  return 0
}
# the processes this test's Slurm started and left (slurmstepd, slurmscriptd,
# a job's tasks): those whose environment holds this test's own SLURM_CONF,
# a path under $T
slurm_children() {
  local e
  for e in /proc/[0-9]*/environ; do
    tr '\0' '\n' 2>/dev/null < "$e" | grep -qxF "SLURM_CONF=$T/slurm.conf" \
      && basename "$(dirname "$e")"
  done 2>/dev/null
}
# stop what this test started, by pid: its job, slurmd, slurmctld, munged,
# then whatever of theirs is left; then the folder
cleanup() {
  if [ -n "$job" ]; then timeout "$CLIENT_TIMEOUT_S" scancel "$job" >/dev/null 2>&1; fi
  local i p
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do stop "${pids[$i]}"; done
  for p in $(slurm_children); do [ "$p" != "$$" ] && [ "$p" != "$BASHPID" ] && stop "$p"; done
  rm -rf "$T"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# the daemons cannot start: skipped with the reason, or failed under CI=true
cannot_start() {
  echo "SKIP: a single-node Slurm cannot start here: $1"
  for f in "$T"/munged.log "$T"/slurmctld.log "$T"/slurmd.log "$T"/*.out; do
    [ -s "$f" ] && { echo "--- $(basename "$f"):"; tail -n 5 "$f"; }
  done
  if [ "${CI:-}" = "true" ]; then
    echo "FAIL: CI=true: the Slurm test must run in CI (bash scripts/quickstart.sh test installs slurm-wlm and munge)"
    echo "0 passed, 1 failed"
    exit 1
  fi
  exit 77
}

for tool in munged munge slurmctld slurmd sbatch squeue sinfo scontrol scancel timeout python3; do
  command -v "$tool" >/dev/null 2>&1 || cannot_start "$tool is missing (apt-get install slurm-wlm munge)"
done

# ---- 1. munged, slurmctld, slurmd from $T --------------------------------------
mkdir -p "$T/munge" "$T/state" "$T/spool" "$T/logs"
head -c 1024 /dev/urandom > "$T/munge/munge.key" && chmod 400 "$T/munge/munge.key"
sock=$T/munge/munge.sock
# -F foreground (this shell holds its pid), -f force: run as whoever runs the test
munged -F -f --key-file="$T/munge/munge.key" --socket="$sock" --pid-file="$T/munge/munged.pid" \
  --log-file="$T/munged.log" --seed-file="$T/munge/munge.seed" >"$T/munged.out" 2>&1 &
pids+=($!)
for _ in $(seq 1 $((DAEMON_WAIT_S * 10))); do [ -S "$sock" ] && break; sleep 0.1; done
[ -S "$sock" ] || cannot_start "munged made no socket in ${DAEMON_WAIT_S} s"
echo x | munge -S "$sock" 2>/dev/null | unmunge -S "$sock" >/dev/null 2>&1 \
  || cannot_start "munge cannot encode and decode a credential through munged"

read -r ctld_port d_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
host=$(hostname -s)
user=$(id -un)
cat > "$T/slurm.conf" <<EOF
# a one-node Slurm for tests/test_slurm.sh, everything under $T
ClusterName=fourbar-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$sock
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmdParameters=config_overrides
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=fourbar Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$T/slurm.conf
slurmctld -D -f "$SLURM_CONF" >"$T/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$T/slurmd.out" 2>&1 &
pids+=($!)
state=""
deadline=$((SECONDS + DAEMON_WAIT_S))
while [ "$SECONDS" -lt "$deadline" ]; do
  state=$(timeout "$CLIENT_TIMEOUT_S" sinfo -h -N -o %T 2>/dev/null | head -n 1)
  [ "$state" = "idle" ] && break
  for p in "${pids[@]}"; do kill -0 "$p" 2>/dev/null || cannot_start "a daemon (pid $p) exited"; done
  sleep 0.5
done
[ "$state" = "idle" ] || cannot_start "the node is '${state:-not listed}' after ${DAEMON_WAIT_S} s, not idle"
echo "single-node Slurm $(slurmctld -V 2>/dev/null | awk '{print $2}') up on $host (ports $ctld_port, $d_port)"

# ---- 2. the shipped script as a job array --------------------------------------
"$exe" sweep "$study" --out "$T/local" >"$T/local.txt" 2>&1
ok '[ "$(wc -l < "$T/local/points.jsonl")" -eq 6 ]' "the study run locally: 6 rows"
job=$(cd "$T/logs" && FOURBAR=$exe timeout "$CLIENT_TIMEOUT_S" sbatch --parsable \
  --array=0-$((shards - 1)) "$script" "$study" "$shards" "$T/slurm" 2>"$T/sbatch.err")
job=${job%%;*}
ok '[ -n "$job" ]' "sbatch accepted the array ($(cat "$T/sbatch.err"))"
left=1
deadline=$((SECONDS + JOB_WAIT_S))
while [ -n "$job" ] && [ "$SECONDS" -lt "$deadline" ]; do
  left=$(timeout "$CLIENT_TIMEOUT_S" squeue -h -j "$job" 2>/dev/null | wc -l)
  [ "$left" -eq 0 ] && break
  sleep 0.5
done
ok '[ "$left" -eq 0 ]' "the array finished within ${JOB_WAIT_S} s"
timeout "$CLIENT_TIMEOUT_S" scontrol -o show job "$job" >"$T/jobs.txt" 2>&1
ok '[ "$(grep -c "JobState=COMPLETED .*ExitCode=0:0" "$T/jobs.txt")" -eq "$shards" ]' \
  "every task COMPLETED with exit code 0: $(grep -o "ArrayTaskId=[0-9]* .*JobState=[A-Z_]*" "$T/jobs.txt" | sed 's/ .*JobState=/ /' | tr '\n' ' ')"
ok '[ "$(ls "$T"/logs/fourbar-sweep-"$job"_*.log 2>/dev/null | wc -l)" -eq "$shards" ]' \
  "each task wrote its log where the script says (fourbar-sweep-%A_%a.log)"
for i in $(seq 0 $((shards - 1))); do
  ok '[ -s "$T/slurm/points.shard-$i-of-$shards.jsonl" ]' "task $i wrote shard $i of $shards"
done

# ---- 3. merged = local, row for row --------------------------------------------
# a merge of folder $1 equals the local run: fourbar merge succeeds, and its
# points.csv is the local one byte for byte and its points.jsonl line for line
merged_equals_local() {
  "$exe" merge "$1" >"$1.merge.txt" 2>&1 || return 1
  cmp -s "$1/points.csv" "$T/local/points.csv" || return 1
  cmp -s <(sort "$1/points.jsonl") <(sort "$T/local/points.jsonl")
}
# copies of the Slurm shards (the merge's input) in folder $1
shards_copy() { mkdir -p "$1" && cp "$T"/slurm/points.shard-* "$1"/; }
shards_copy "$T/merge"
merged_equals_local "$T/merge"; same=$?
ok '[ "$same" -eq 0 ]' "merged Slurm shards equal the local run row for row ($(tail -n 1 "$T/merge.merge.txt"))"

# ---- 4. the comparison fails on a lost or duplicated row -----------------------
shards_copy "$T/lost"
sed -i '$d' "$T/lost/points.shard-1-of-$shards.jsonl"
ok '! merged_equals_local "$T/lost"' "a row of shard 1 lost: the merge is not the local run"
ok 'grep -q "missing" "$T/lost.merge.txt"' "a row lost: merge names the missing point"
shards_copy "$T/dup"
head -n 1 "$T/dup/points.shard-0-of-$shards.jsonl" >> "$T/dup/points.shard-2-of-$shards.jsonl"
ok '! merged_equals_local "$T/dup"' "a row of shard 0 repeated in shard 2: the merge is not the local run"
ok 'grep -q "more than once" "$T/dup.merge.txt"' "a row duplicated: merge names it"
shards_copy "$T/noshard"
rm "$T"/noshard/points.shard-2-of-$shards.*
ok '! merged_equals_local "$T/noshard"' "shard 2 lost: the merge is not the local run"

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
