#!/bin/bash
# A single-node Slurm cluster in a folder, for tests and for trying a plan on one machine:
#   scripts/slurm-local.sh start DIR   # munged, slurmctld and slurmd, all state under DIR; prints the
#                                      # line to export (SLURM_CONF) for sbatch, squeue and scontrol
#   scripts/slurm-local.sh stop DIR    # stops the three daemons started by `start DIR`
# Debian's slurm-wlm and munge, as root, without systemd: the non-cgroup plugins (proctrack/linuxproc,
# task/none), no accounting, the node's memory as `slurmd -C` reports it (never more), ports chosen per
# folder so that two clusters on one machine do not meet. A studio's own cluster needs none of this:
# see docs/worlds.md.
set -euo pipefail

usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
dir=$(mkdir -p "$2" && cd "$2" && pwd)
conf=$dir/slurm.conf

stop_pidfile() {
  local f=$1
  [ -f "$f" ] || return 0
  local pid; pid=$(cat "$f" 2>/dev/null || true)
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  fi
  rm -f "$f"
}

case "$action" in
stop)
  stop_pidfile "$dir/slurmd.pid"
  stop_pidfile "$dir/slurmctld.pid"
  stop_pidfile "$dir/munge/munged.pid"
  exit 0 ;;
start) ;;
*) usage ;;
esac

for tool in munged slurmctld slurmd sbatch sinfo; do
  command -v "$tool" >/dev/null || { echo "$0: $tool is missing: apt-get install slurm-wlm munge" >&2; exit 1; }
done
[ "$(id -u)" -eq 0 ] || { echo "$0: start needs root (slurmd runs jobs as their users)" >&2; exit 1; }

mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
chmod 700 "$dir/munge"
if [ ! -s "$dir/munge/munge.key" ]; then
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
fi
chmod 400 "$dir/munge/munge.key"
socket=$dir/munge/munge.socket
munged --force --key-file="$dir/munge/munge.key" --socket="$socket" --pid-file="$dir/munge/munged.pid" \
  --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed"

# The node as slurmd sees it (CPUs, sockets, cores, memory): declaring more than it has would drain it.
node_line=$(slurmd -C | head -1)
node=$(sed -n 's/^NodeName=\([^ ]*\).*/\1/p' <<<"$node_line")
# Ports from the folder's name, so that each folder's cluster has its own.
base=$(( 20000 + $(cksum <<<"$dir" | cut -d' ' -f1) % 20000 ))
cat >"$conf" <<CONF
# Written by scripts/slurm-local.sh: a single-node cluster whose state lives in $dir.
ClusterName=undergrowth
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$base
SlurmdPort=$((base + 1))
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
# Schedule at once: a batch job is not held back (default 3 s), so a dependency's successor starts as
# soon as its predecessor ends.
SchedulerParameters=batch_sched_delay=0
ReturnToService=2
JobRequeue=1
MinJobAge=3600
InactiveLimit=0
KillWait=5
$node_line NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF

export SLURM_CONF=$conf
slurmctld -f "$conf"
slurmd -f "$conf" -N "$node"
for _ in $(seq 100); do
  state=$(sinfo -h -N -o %t 2>/dev/null | head -1 || true)
  case "$state" in idle|mix|alloc) echo "export SLURM_CONF=$conf"; exit 0 ;; esac
  sleep 0.2
done
echo "$0: the node did not come up (state '${state:-none}'); see $dir/log/" >&2
"$0" stop "$dir"
exit 1
