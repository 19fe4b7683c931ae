#!/usr/bin/env bash
# docs/scale.md's Slurm recipe on a real single-node Slurm cluster (issue 26 item 4): slurmctld,
# slurmd and munged from Debian's packages, started here without systemd or cgroups in a temporary
# directory (own munge key and socket, free ports, state and logs), run shards.sbatch and
# merge.sbatch as the page writes them (taken out of the page, not copied), check the merged report
# against the unsharded run byte for byte, check that a failing array cancels the merge, and stop
# every process started here, on failure too. Bounded: 60 s in all.
#   tests/cluster/slurm_shards.sh ERR_SIM_DIR SCALE_MD CHAIN
# Exit 0 passed, 1 failed, 77 skipped (not root: slurmd starts jobs as their user).
set -euo pipefail
tools=$(cd "$1" && pwd)
doc=$2
chain=$3
start=$SECONDS
limit=50  # the work; stopping the cluster takes at most 10 s more: 60 s in all

[ "$(id -u)" -eq 0 ] || { echo "slurm_shards: skipped: needs root (slurmd runs jobs as their owner)"; exit 77; }
for program in munged mungekey slurmctld slurmd sbatch squeue scontrol sinfo; do
  command -v "$program" >/dev/null || { echo "slurm_shards: $program is missing: run scripts/setup" >&2; exit 1; }
done

# Every process of the cluster lives in a PID namespace of its own when the machine allows one: a
# job step that outlives the kill below (slurmstepd detaches from slurmd) dies with the namespace.
if [ -z "${SLURM_SHARDS_INSIDE:-}" ] && unshare --fork --pid --mount-proc --kill-child true 2>/dev/null; then
  SLURM_SHARDS_INSIDE=1 exec unshare --fork --pid --mount-proc --kill-child bash "$0" "$@"
fi

tmp=$(mktemp -d /tmp/slurm-shards.XXXXXX)
pids=()
stop() {
  local status=$?
  # The jobs first (their processes are slurmstepd's, not ours), then the daemons by their PIDs.
  if [ -n "${SLURM_CONF:-}" ] && [ ${#pids[@]} -gt 1 ]; then
    timeout 5 scancel --full "--partition=vstcal" 2>/dev/null || true
  fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null || true; done
  for _ in $(seq 50); do
    alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ $alive -eq 0 ] && break
    sleep 0.1
  done
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
  if [ $status -ne 0 ]; then
    for log in "$tmp"/log/*.log "$tmp"/run/logs/*.log; do
      [ -f "$log" ] && { echo "--- $log"; tail -n 20 "$log"; }
    done
  fi
  rm -rf "$tmp"
  echo "slurm_shards: cluster stopped, $((SECONDS - start)) s in all" >&2
  exit $status
}
trap stop EXIT
trap 'exit 1' INT TERM

fail() { echo "slurm_shards: FAILED: $*" >&2; exit 1; }
left() { echo $((limit - (SECONDS - start))); }
# wait_for SECONDS DESCRIPTION COMMAND...: polls COMMAND every 0.1 s until it succeeds.
wait_for() {
  local seconds=$1 what=$2
  shift 2
  local until=$((SECONDS + seconds))
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $until ] || fail "$what: not within $seconds s"
    sleep 0.1
  done
}

mkdir -p "$tmp"/{etc,munge,log,state,spool,run/shards,run/logs}
chmod 700 "$tmp/munge"
# A free TCP port on the loopback for each daemon (no fixed port: two runs may overlap).
free_ports() {
  /usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))'
}
read -r ctld_port slurmd_port < <(free_ports)

# munge: a private key and socket.
mungekey --create --keyfile="$tmp/munge/munge.key" --bits=1024 >/dev/null 2>&1 ||
  { dd if=/dev/urandom of="$tmp/munge/munge.key" bs=128 count=1 status=none; }
chmod 400 "$tmp/munge/munge.key"
socket=$tmp/munge/munge.socket
munged --foreground --socket="$socket" --key-file="$tmp/munge/munge.key" --pid-file="$tmp/munge/munged.pid" \
  --log-file="$tmp/log/munged.log" --seed-file="$tmp/munge/munged.seed" --force 2>/dev/null &
pids+=($!)
wait_for 5 "munged's socket" test -S "$socket"

# slurm.conf: one node with the machine's CPUs and memory as slurmd sees them.
node=$(slurmd -C | sed -n 's/^NodeName=\([^ ]*\).*/\1/p')
hardware=$(slurmd -C | head -n 1 | sed 's/^NodeName=[^ ]* //')
cat >"$tmp/etc/slurm.conf" <<CONF
ClusterName=vstcal
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
MailProg=/bin/true
MpiDefault=none
ReturnToService=2
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/state/slurmctld.pid
SlurmdPidFile=$tmp/spool/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
SlurmctldTimeout=10
SlurmdTimeout=10
MinJobAge=60
NodeName=$node NodeAddr=127.0.0.1 $hardware State=UNKNOWN
PartitionName=vstcal Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/etc/slurm.conf
slurmctld -D -c -f "$SLURM_CONF" 2>/dev/null &
pids+=($!)
slurmd -D -f "$SLURM_CONF" 2>/dev/null &
pids+=($!)
node_idle() { [ "$(sinfo -h -n "$node" -o %t)" = idle ]; }
wait_for 15 "the node to be idle" node_idle
echo "slurm_shards: cluster up in $((SECONDS - start)) s (node $node: $hardware)" >&2

# The page's scripts and lines, taken out of it: the code block after a line "`NAME`:", the inline
# command of the small-run sentence, and the merge's submission line.
block_after() { awk -v want="\`$1\`:" '$0 == want {found = 1; next} found && /^```/ {if (inside) exit; inside = 1; next} inside' "$doc"; }
block_after shards.sbatch >"$tmp/run/shards.sbatch"
block_after merge.sbatch >"$tmp/run/merge.sbatch"
small_run=$(grep -o '`SAMPLES=[^`]*sbatch --parsable --array=[^`]*shards.sbatch`' "$doc" | tr -d '`')
merge_line=$(grep -m1 '^sbatch --dependency=afterok:"\$array"' "$doc")
[ -s "$tmp/run/shards.sbatch" ] && [ -s "$tmp/run/merge.sbatch" ] && [ -n "$small_run" ] && [ -n "$merge_line" ] ||
  fail "cannot find shards.sbatch, merge.sbatch and the submission lines in $doc"
grep -q -- '--kill-on-invalid-dep=yes' <<<"$merge_line" || fail "the page's merge line lacks --kill-on-invalid-dep=yes"

# The chain and the camera file it names (../zedmini/…) laid out as in datasets/.
chain_dir=$(cd "$(dirname "$chain")" && pwd)
mkdir -p "$tmp/zedmini"
cp "$chain_dir"/../zedmini/*.json "$tmp/zedmini/"
cp "$chain" "$tmp/run/chain.json"
mv "$tmp/run" "$tmp/vst" && mkdir -p "$tmp/vst/shards" "$tmp/vst/logs"
cd "$tmp/vst"
export PATH=$tools:$PATH

# job_state ID: COMPLETED, PENDING, CANCELLED, ...
job_state() { scontrol -o show job "$1" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n 1; }
ended() { case $(job_state "$1") in COMPLETED | FAILED | CANCELLED | TIMEOUT | OUT_OF_MEMORY | NODE_FAIL) return 0 ;; *) return 1 ;; esac; }

array=$(eval "$small_run")
merge=$(eval "${merge_line/sbatch /sbatch --parsable }")
wait_for "$(left)" "the merge job $merge to end" ended "$merge"
[ "$(job_state "$merge")" = COMPLETED ] || fail "merge job $merge ended $(job_state "$merge")"
echo "slurm_shards: 4 shards and the merge ran in $((SECONDS - start)) s" >&2

# The unsharded run, with the same sizes; the provenance differs (the command lines), nothing else.
samples=$(sed 's/^SAMPLES=\([0-9]*\) .*/\1/' <<<"$small_run")
budget=$(sed 's/.*BUDGET_SAMPLES=\([0-9]*\) .*/\1/' <<<"$small_run")
err-sim run chain.json --samples "$samples" --budget-samples "$budget" -q -o single.json
strip() { /usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); r.pop("provenance"); print(json.dumps(r, indent=1))' "$1" >"$2"; }
strip report.json merged.nop.json
strip single.json single.nop.json
cmp merged.nop.json single.nop.json || { diff merged.nop.json single.nop.json | head -n 20 >&2; fail "the merged report differs from the unsharded run"; }
echo "slurm_shards: the merged report equals the unsharded run byte for byte ($(wc -c <merged.nop.json) bytes)" >&2

# A failing array (a sample count err-sim refuses) must cancel the merge, not leave it pending.
rm -f shards/*.json
array=$(eval "${small_run/SAMPLES=$samples /SAMPLES=0 }")
merge=$(eval "${merge_line/sbatch /sbatch --parsable }")
wait_for "$(left)" "the merge behind a failed array to be cancelled" ended "$merge"
[ "$(job_state "$merge")" = CANCELLED ] || fail "merge job $merge behind a failed array ended $(job_state "$merge")"
echo "slurm_shards: a failed array cancels the merge (--kill-on-invalid-dep=yes)" >&2
echo "slurm_shards: passed in $((SECONDS - start)) s"
