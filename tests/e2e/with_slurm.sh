#!/usr/bin/env bash
# Runs a command against a private single-node Slurm cluster started here and
# stopped afterwards, even when the command fails (../shared/slurm.md recipe):
# munge key and socket, state, spool and logs in one temporary folder, a
# private SLURM_CONF, free non-default ports; nothing in /etc, /var or /run.
#   tests/e2e/with_slurm.sh COMMAND [ARGS...]
# The command sees SLURM_CONF. Fails (exit 1) when slurmctld, slurmd, munged
# or the Slurm clients are missing: scripts/setup.sh installs them.
set -euo pipefail

for tool in slurmctld slurmd munged mungekey munge sbatch squeue scontrol sinfo; do
  if ! command -v "$tool" >/dev/null 2>&1 && [ ! -x "/usr/sbin/$tool" ]; then
    echo "with_slurm.sh: $tool not found: install slurmctld slurmd slurm-client munge" \
         "(scripts/setup.sh does)" >&2
    exit 1
  fi
done
export PATH="$PATH:/usr/sbin"

D=$(mktemp -d /tmp/storey-slurm.XXXXXX)
chmod 711 "$D"
mkdir -p "$D/munge" "$D/state" "$D/spool" "$D/log"
chmod 711 "$D/munge"
PIDS=()

stop_cluster() {
  local status=$?
  set +e
  # The PIDs first: the daemons delete their pid files when they stop.
  for f in "$D/slurmctld.pid" "$D/slurmd.pid" "$D/munge/munged.pid"; do
    [ -s "$f" ] && PIDS+=("$(cat "$f")")
  done
  SLURM_CONF="$D/slurm.conf" scontrol shutdown >/dev/null 2>&1
  for pid in "${PIDS[@]}"; do kill -TERM "$pid" 2>/dev/null; done
  for _ in $(seq 1 100); do
    alive=0
    for pid in "${PIDS[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ $alive -eq 0 ] && break
    sleep 0.1
  done
  for pid in "${PIDS[@]}"; do kill -KILL "$pid" 2>/dev/null; done
  if [ $status -ne 0 ] && [ -f "$D/log/slurmctld.log" ]; then
    echo "with_slurm.sh: last lines of slurmctld.log and slurmd.log:" >&2
    tail -n 15 "$D/log/slurmctld.log" "$D/log/slurmd.log" >&2
  fi
  rm -rf "$D"
  exit $status
}
trap stop_cluster EXIT
trap 'exit 130' INT TERM

free_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}
CTLD_PORT=$(free_port)
SLURMD_PORT=$(free_port)
while [ "$SLURMD_PORT" = "$CTLD_PORT" ]; do SLURMD_PORT=$(free_port); done

mungekey --create --force --keyfile="$D/munge/munge.key" 2>/dev/null
chmod 600 "$D/munge/munge.key"
munged --force --socket="$D/munge/munge.sock" --key-file="$D/munge/munge.key" \
  --log-file="$D/munge/munged.log" --pid-file="$D/munge/munged.pid" \
  --seed-file="$D/munge/munged.seed" --origin=127.0.0.1 </dev/null 2>/dev/null
munge -n -S "$D/munge/munge.sock" | unmunge -S "$D/munge/munge.sock" >/dev/null

HOST=$(hostname -s)
MEM_MB=$(awk '/MemTotal/ {print int($2 / 1024)}' /proc/meminfo)
# CPUs=8 on any machine: tiny tasks run several at once (SlurmdParameters=config_overrides).
cat >"$D/slurm.conf" <<CONF
ClusterName=storeytest
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/munge/munge.sock
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
PlugStackConfig=$D/plugstack.conf
MailProg=/bin/true
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$D/log/jobcomp.txt
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
SlurmdParameters=config_overrides
ReturnToService=2
MinJobAge=3600
InactiveLimit=0
KillWait=5
Waittime=0
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=8 RealMemory=$MEM_MB State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
: >"$D/plugstack.conf"
export SLURM_CONF="$D/slurm.conf"

slurmctld -L "$D/log/slurmctld.log" </dev/null
slurmd -L "$D/log/slurmd.log" </dev/null
for _ in $(seq 1 300); do
  [ "$(sinfo -h -N -o %T 2>/dev/null | head -n 1)" = "idle" ] && break
  sleep 0.1
done
if [ "$(sinfo -h -N -o %T 2>/dev/null | head -n 1)" != "idle" ]; then
  echo "with_slurm.sh: the node did not become idle in 30 s" >&2
  exit 1
fi
echo "with_slurm.sh: cluster up (SLURM_CONF=$SLURM_CONF, ports $CTLD_PORT/$SLURMD_PORT)" >&2
"$@"
