#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for campaigns through `roverctl run --backend slurm`
# and for their integration test: munged, slurmctld and slurmd from Debian's packages
# (scripts/setup.sh installs them), with a generated slurm.conf. Runs as root (as CI does).
#
# Usage: scripts/slurm-local.sh start|stop|status
#   start   writes /etc/slurm/slurm.conf (only if absent or written by this script), starts the
#           three daemons if they are not running, waits until the node is idle (at most 60 s)
#   stop    stops the daemons this script started
#   status  sinfo's view of the node
#
# The node takes every CPU of the machine (SelectType cons_tres, CR_CPU: a run per CPU asked);
# no cgroups (proctrack/linuxproc, task/none), no accounting database.
set -euo pipefail
CONF=/etc/slurm/slurm.conf
MARK="# written by rover scripts/slurm-local.sh"
LOGDIR=/var/log/rover-slurm

die() { echo "slurm-local: $*" >&2; exit 1; }

need() {
  for b in munged slurmctld slurmd sbatch sinfo; do
    command -v "$b" >/dev/null 2>&1 || [[ -x /usr/sbin/$b ]] ||
      die "'$b' is missing: run scripts/setup.sh (Debian packages munge, slurmctld, slurmd, slurm-client)"
  done
  [[ $(id -u) -eq 0 ]] || die "run as root (the daemons need it)"
}

write_conf() {
  if [[ -f $CONF ]] && ! grep -qF "$MARK" "$CONF"; then
    die "$CONF exists and was not written by this script: not touching it"
  fi
  local host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  mem=$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)
  mkdir -p /etc/slurm /var/spool/slurmctld /var/spool/slurmd "$LOGDIR"
  cat > "$CONF" <<CONF
$MARK
ClusterName=rover
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=$LOGDIR/slurmctld.log
SlurmdLogFile=$LOGDIR/slurmd.log
SlurmdTimeout=60
InactiveLimit=0
MinJobAge=300
KillWait=10
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=rover Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
}

running() { pgrep -x "$1" >/dev/null 2>&1; }

start() {
  need
  write_conf
  if ! running munged; then
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge
    [[ -f /etc/munge/munge.key ]] || { dd if=/dev/urandom of=/etc/munge/munge.key bs=1 count=128 status=none; chown munge:munge /etc/munge/munge.key; chmod 0400 /etc/munge/munge.key; }
    runuser -u munge -- /usr/sbin/munged
  fi
  running slurmctld || /usr/sbin/slurmctld
  running slurmd || /usr/sbin/slurmd
  local host
  host=$(hostname -s)
  for _ in $(seq 1 60); do
    state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
    if [[ $state == idle* || $state == mixed* || $state == allocated* ]]; then
      echo "slurm-local: node $host is $state (partition rover, $(nproc) CPUs); logs in $LOGDIR"
      return 0
    fi
    if [[ $state == down* || $state == drain* ]]; then
      scontrol update nodename="$host" state=resume >/dev/null 2>&1 || true
    fi
    sleep 1
  done
  die "the node did not become idle in 60 s (state '${state:-none}'); see $LOGDIR"
}

stop() {
  for d in slurmd slurmctld munged; do
    pkill -x "$d" 2>/dev/null || true
  done
  echo "slurm-local: stopped"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status) sinfo ;;
  *) echo "usage: $0 start|stop|status" >&2; exit 2 ;;
esac
