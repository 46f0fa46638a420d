#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, in a folder of its own: munged,
# slurmctld and slurmd from Debian's munge and slurm-wlm packages, run as root
# with their configuration, state, sockets and logs in DIR (nothing under
# /etc is touched). For the cluster tests and for trying scripts/slurm/submit.sh.
#   scripts/slurm/local-cluster.sh start DIR   starts it; prints the line to
#                                              export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm/local-cluster.sh stop DIR    stops it (the folder stays)
# Ports: $SLURM_PORT (default 17817) and the next one. Needs root.
set -euo pipefail
cmd=${1:-}
dir=${2:-}
[ -n "$cmd" ] && [ -n "$dir" ] || { sed -n 2,9p "$0" >&2; exit 2; }
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
export SLURM_CONF=$dir/slurm.conf
# Unix socket paths (munged's, slurmstepd's in the spool) must fit 108
# bytes: a deep DIR keeps them in a short folder under /tmp instead.
run=$dir
if [ ${#dir} -gt 48 ]; then
  run=/tmp/globe-slurm-$(printf '%s' "$dir" | md5sum | cut -c1-12)
fi
sock=$run/munge.sock

stop() {
  if [ -f "$dir/slurmctld.pid" ] || [ -f "$dir/slurmd.pid" ]; then
    scontrol shutdown >/dev/null 2>&1 || true
    for pid_file in "$dir/slurmd.pid" "$dir/slurmctld.pid"; do
      [ -f "$pid_file" ] || continue
      pid=$(cat "$pid_file")
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
      rm -f "$pid_file"
    done
  fi
  [ -S "$sock" ] && munged -s -S "$sock" >/dev/null 2>&1 || true
  rm -f "$sock"
  [ "$run" = "$dir" ] || rm -rf "$run"
}

case "$cmd" in
stop)
  stop
  exit 0
  ;;
start) ;;
*)
  echo "local-cluster.sh: unknown command '$cmd' (start or stop)" >&2
  exit 2
  ;;
esac

[ "$(id -u)" -eq 0 ] || { echo "local-cluster.sh: needs root (slurmd runs jobs as their user)" >&2; exit 1; }
for tool in munged slurmctld slurmd scontrol sinfo; do
  command -v "$tool" >/dev/null ||
    { echo "local-cluster.sh: $tool is missing; run scripts/install-deps.sh (munge, slurm-wlm)" >&2; exit 1; }
done
stop
mkdir -p "$dir/state" "$run/spool" "$dir/log"
if [ ! -f "$dir/munge.key" ]; then
  head -c 1024 /dev/urandom >"$dir/munge.key"
  chmod 600 "$dir/munge.key"
fi
munged --force -S "$sock" --key-file="$dir/munge.key" --log-file="$dir/log/munged.log" \
  --pid-file="$dir/munged.pid" --seed-file="$dir/munged.seed"
host=$(hostname -s)
port=${SLURM_PORT:-17817}
cat >"$SLURM_CONF" <<CONF
ClusterName=globelocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$run/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=globe Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 100); do
  if sinfo -h -o %t 2>/dev/null | grep -qx idle; then
    echo "export SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.2
done
echo "local-cluster.sh: the node did not come up; see $dir/log/" >&2
tail -5 "$dir/log/slurmctld.log" "$dir/log/slurmd.log" >&2 || true
stop
exit 1
