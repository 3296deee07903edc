#!/usr/bin/env bash
# Start a private single-node Slurm cluster (munged + slurmctld + slurmd) whose
# config, state, logs and sockets all live under DIR.  Nothing in /etc, /run or
# /var is read or written, so it can coexist with a system Slurm/munge.
# Usage: slurm-up.sh DIR      then:  source DIR/env.sh   (stop: slurm-down.sh DIR)
set -euo pipefail

[[ $# -eq 1 ]] || { echo "usage: $0 DIR" >&2; exit 2; }
mkdir -p "$1"
DIR=$(cd "$1" && pwd)          # daemons chdir, so every path must be absolute
HERE=$(cd "$(dirname "$0")" && pwd)
NODE=$(hostname -s)
USER_NAME=$(id -un)
CONF=$DIR/slurm.conf

# A second 'up' on a live DIR would, on failure, tear down the first cluster.
for f in "$DIR"/{munged,slurmctld,slurmd}.pid; do
  [[ -e $f ]] && { echo "slurm-up: $f exists; run slurm-down.sh $DIR first" >&2; exit 1; }
done

# munged rejects a group/world-writable socket dir and warns when clients can't
# traverse it (mktemp -d gives 0700), so normalise the mode.
chmod 0755 "$DIR"
mkdir -p "$DIR/state" "$DIR/spool" "$DIR/tmp"

fail() {
  echo "slurm-up: $*" >&2
  for f in munged.log slurmctld.log slurmd.log; do
    [[ -f $DIR/$f ]] && { echo "---- tail $DIR/$f" >&2; tail -n 25 "$DIR/$f" >&2; }
  done
  "$HERE/slurm-down.sh" "$DIR" >&2 || true
  exit 1
}

# Free TCP port search starting from a PID-derived base, so parallel test runs
# (and a system slurm on 6817/6818) don't collide.
free_port() {
  local p=$1
  command -v ss >/dev/null || { echo "$p"; return; }
  while ss -Htan "sport = :$p" | grep -q .; do p=$((p + 1)); done
  echo "$p"
}
CTLD_PORT=$(free_port $((20000 + ($$ % 2000) * 10)))
SLURMD_PORT=$(free_port $((CTLD_PORT + 1)))

# ---- munge: private key + daemon on a private socket ----------------------
if [[ ! -f $DIR/munge.key ]]; then
  if command -v mungekey >/dev/null; then
    mungekey --create --keyfile "$DIR/munge.key"
  else
    dd if=/dev/urandom of="$DIR/munge.key" bs=1024 count=1 status=none
  fi
fi
chmod 0400 "$DIR/munge.key"
# --force turns munged's fatal "insecure permissions" checks on DIR and its
# ancestors (e.g. a group-writable build tree) into warnings.  munged forks
# only once its socket is ready, so no wait is needed.
munged --force \
  --socket="$DIR/munge.socket" --key-file="$DIR/munge.key" \
  --pid-file="$DIR/munged.pid" --log-file="$DIR/munged.log" \
  --seed-file="$DIR/munged.seed" || fail "munged did not start"

# ---- slurm.conf -----------------------------------------------------------
# Not nproc: it honours OMP_NUM_THREADS, which tests set to 1.
NCPU=$(getconf _NPROCESSORS_ONLN)
# Leave headroom below what slurmd detects, else the node is drained
# (Low RealMemory) when the figure fluctuates.
MEM=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
MEM=$(( MEM > 1024 ? MEM - 512 : MEM ))

cat > "$CONF" <<CONF
ClusterName=clatter-test
# Explicit 127.0.0.1 so nothing depends on DNS/hosts for the short hostname.
SlurmctldHost=$NODE(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
# Run everything as the invoking user (root in CI); slurmd must be root to
# launch jobs.
SlurmUser=$USER_NAME
SlurmdUser=root
# One socket for auth and job-step credentials, used by daemons and clients.
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge.socket
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
# mpi/pmix puts its per-step rendezvous dirs here (default /tmp).
TmpFS=$DIR/tmp
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups: works in containers and without systemd delegation.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=pmix
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# A job that can never run is refused at submission instead of pending forever.
EnforcePartLimits=ALL
ReturnToService=2
# Fast turnaround for tests: schedule every second, no batch-delay, keep
# finished jobs visible to scontrol for 30 s, short kill grace.
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,batch_sched_delay=0,bf_interval=1
MinJobAge=30
KillWait=2
InactiveLimit=0
Waittime=0
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$NCPU RealMemory=$MEM State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
CONF

cat > "$DIR/env.sh" <<ENV
export SLURM_CONF=$CONF
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
ENV
export SLURM_CONF=$CONF

# ---- slurm daemons (they daemonize and write their pid files) ------------
# -c: ignore any state left in a reused DIR.
slurmctld -c -f "$CONF" || fail "slurmctld did not start"
slurmd -f "$CONF" -N "$NODE" || fail "slurmd did not start"

# The node registers asynchronously; only 'idle' means jobs can start.
for _ in $(seq 60); do
  state=$(sinfo -h -N -n "$NODE" -o %t 2>/dev/null || true)
  [[ $state == idle ]] && { cat "$DIR/env.sh"; exit 0; }
  sleep 0.5
done
fail "node $NODE not idle after 30 s (state: '${state:-none}')"
