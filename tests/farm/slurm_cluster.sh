#!/usr/bin/env bash
# Sourced: starts a real single-node Slurm here (munge, slurmctld, slurmd; no systemd) in a
# temporary directory $d (jobs may write in $d/work), exports SLURM_CONF and stops it all on
# exit. Installs the Debian packages when missing. Needs root; the caller checks.
#
#   . tests/farm/slurm_cluster.sh
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v sbatch >/dev/null ||
  ! command -v munged >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y --no-install-recommends slurmctld slurmd slurm-client munge >/dev/null ||
    { apt-get update >/dev/null && apt-get install -y --no-install-recommends slurmctld slurmd slurm-client munge >/dev/null; }
fi

d="$(mktemp -d /tmp/nxslurm.XXXXXX)"
chmod 755 "$d"
pids=()
stop_cluster() {
  # Read the daemons' PIDs first (they delete their pid files while stopping), then wait.
  local p
  for f in "$d/slurmd.pid" "$d/slurmctld.pid" "$d/munged.pid"; do
    [ -f "$f" ] && pids+=("$(cat "$f")")
  done
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do
    for _ in $(seq 100); do
      if ! kill -0 "$p" 2>/dev/null || grep -q '^State:.*Z' "/proc/$p/status" 2>/dev/null; then break; fi
      sleep 0.1
    done
  done
  rm -rf "$d"
}
trap stop_cluster EXIT

# munge with a private key and socket directory (world-executable).
mkdir -p "$d/munge" "$d/state" "$d/spool" "$d/work"
chmod 755 "$d/munge"
dd if=/dev/urandom of="$d/munge.key" bs=1024 count=1 status=none
chmod 400 "$d/munge.key"
munged --force --key-file="$d/munge.key" --socket="$d/munge/munge.socket" --pid-file="$d/munged.pid" \
  --log-file="$d/munged.log" --seed-file="$d/munge.seed"

topology="$(slurmd -C | head -n 1 | grep -o 'CPUs=.*ThreadsPerCore=[0-9]*')"
cat >"$d/slurm.conf" <<CONF
ClusterName=nxtest
SlurmctldHost=localhost
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$d/munge/munge.socket
SlurmUser=root
SlurmdUser=root
SlurmctldPort=46817
SlurmdPort=46818
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
SchedulerParameters=batch_sched_delay=0
DependencyParameters=kill_invalid_depend
MinJobAge=600
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 $topology State=UNKNOWN
PartitionName=main Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$d/slurm.conf"
slurmctld
slurmd -N localhost
for _ in $(seq 100); do
  if sinfo -h -o '%T' 2>/dev/null | grep -q idle; then break; fi
  sleep 0.2
done
sinfo -h -o '%T' | grep -q idle || { echo "slurm did not come up"; cat "$d"/*.log; exit 1; }

