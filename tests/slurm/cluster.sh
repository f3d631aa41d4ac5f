#!/usr/bin/env bash
# A one-node Slurm cluster in a temporary directory, for the `slurm` tests.
#   tests/slurm/cluster.sh install     install slurm-wlm and munge (Debian, root)
#   tests/slurm/cluster.sh start DIR   write DIR/slurm.conf (proctrack/linuxproc,
#                                      task/none, no accounting database), start
#                                      munged, slurmctld and slurmd with pid files
#                                      in DIR, wait until the node is idle
#   tests/slurm/cluster.sh stop DIR    stop exactly the daemons started in DIR
# Commands then need SLURM_CONF=DIR/slurm.conf.
set -euo pipefail
cmd="${1:-}"
dir="${2:-}"

need() {
  for p in /usr/sbin/munged /usr/sbin/slurmctld /usr/sbin/slurmd /usr/bin/sbatch; do
    if [ ! -x "$p" ]; then
      echo "cluster.sh: $p is missing: run 'tests/slurm/cluster.sh install' as root" >&2
      exit 2
    fi
  done
}

case "$cmd" in
  install)
    missing=()
    for p in slurm-wlm munge; do
      dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if ((${#missing[@]})); then
      sudo_cmd=()
      [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
      export DEBIAN_FRONTEND=noninteractive
      "${sudo_cmd[@]}" apt-get update -q
      "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
    fi
    ;;
  start)
    need
    [ -n "$dir" ] || { echo "usage: cluster.sh start DIR" >&2; exit 2; }
    mkdir -p "$dir"/{state,spool,log,run,munge}
    chmod 700 "$dir/munge"
    dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
    chmod 400 "$dir/munge/munge.key"
    host="$(hostname)"
    base=$((20000 + ($$ % 4000) * 2))
    cat >"$dir/slurm.conf" <<CONF
ClusterName=splattest
SlurmctldHost=$host
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.sock
CredType=cred/munge
SlurmctldPort=$base
SlurmdPort=$((base + 1))
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/run/slurmctld.pid
SlurmdPidFile=$dir/run/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
MaxArraySize=1001
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
    /usr/sbin/munged --force --socket="$dir/munge/munge.sock" --key-file="$dir/munge/munge.key" \
      --log-file="$dir/log/munged.log" --pid-file="$dir/munge/munged.pid" \
      --seed-file="$dir/munge/seed"
    export SLURM_CONF="$dir/slurm.conf"
    /usr/sbin/slurmctld -c
    /usr/sbin/slurmd
    for _ in $(seq 1 100); do
      if sinfo --noheader --format=%t 2>/dev/null | grep -q idle; then
        echo "SLURM_CONF=$dir/slurm.conf"
        exit 0
      fi
      sleep 0.2
    done
    echo "cluster.sh: the node did not become idle; logs in $dir/log" >&2
    exit 1
    ;;
  stop)
    [ -n "$dir" ] || { echo "usage: cluster.sh stop DIR" >&2; exit 2; }
    for f in "$dir/run/slurmd.pid" "$dir/run/slurmctld.pid" "$dir/munge/munged.pid"; do
      if [ -f "$f" ]; then
        pid="$(cat "$f")"
        kill "$pid" 2>/dev/null || true
        for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      fi
    done
    ;;
  *)
    echo "usage: cluster.sh install | start DIR | stop DIR" >&2
    exit 2
    ;;
esac
