#!/usr/bin/env bash
# A real one-node SLURM cluster for the scan tests: munged, slurmctld and slurmd started by
# hand (no systemd here) with their state in DIR, stopped by PID.
#   bash tests/slurm/cluster.sh start DIR    # exits non-zero if the node is not idle in 30 s
#   bash tests/slurm/cluster.sh stop DIR
# SLURM_CONF=DIR/slurm.conf must be set for sbatch, squeue and scontrol.
set -euo pipefail
action=${1:?start|stop}
dir=${2:?state folder}
case $action in
start)
  mkdir -p "$dir"/{state,spool,log}
  install -d -o munge -g munge -m 0755 /run/munge
  if ! pgrep -x munged > /dev/null || [ ! -S /run/munge/munge.socket.2 ]; then
    runuser -u munge -- /usr/sbin/munged --force
    touch "$dir/munged.started"  # ours to stop
  fi
  host=$(hostname)
  cpus=$(nproc)
  memory=$(( $(free -m | awk '/^Mem:/ {print $7}') / 2 ))
  cat > "$dir/slurm.conf" <<CONF
ClusterName=ddafit-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MaxArraySize=100001
NodeName=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"
  /usr/sbin/slurmctld -D -f "$SLURM_CONF" > "$dir/log/slurmctld.out" 2>&1 &
  echo $! > "$dir/slurmctld.daemon"
  /usr/sbin/slurmd -D -f "$SLURM_CONF" > "$dir/log/slurmd.out" 2>&1 &
  echo $! > "$dir/slurmd.daemon"
  for _ in $(seq 1 60); do
    if sinfo -h -o %T 2>/dev/null | grep -qx idle; then exit 0; fi
    sleep 0.5
  done
  echo "cluster.sh: the SLURM node did not become idle in 30 s; logs in $dir/log" >&2
  sinfo 2>&1 | head -5 >&2 || true
  exit 1
  ;;
stop)
  # Each daemon is waited for (up to 10 s): a munged still exiting when the next test's
  # start looks for one is taken as running, and its socket then vanishes under that test.
  pids=()
  for daemon in slurmd slurmctld; do
    if [ -f "$dir/$daemon.daemon" ]; then pids+=("$(cat "$dir/$daemon.daemon")"); fi
  done
  if [ -f "$dir/munged.started" ] && [ -f /run/munge/munged.pid ]; then pids+=("$(cat /run/munge/munged.pid)"); fi
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
  done
  ;;
*) echo "cluster.sh: start or stop" >&2; exit 2 ;;
esac
