#!/usr/bin/env bash
# Stop the private cluster started by slurm-up.sh DIR.  Only the PIDs recorded
# in DIR are signalled (never by name) so other Slurm/munge instances survive.
# Idempotent: missing or stale pid files are ignored.
set -euo pipefail

[[ $# -eq 1 ]] || { echo "usage: $0 DIR" >&2; exit 2; }
DIR=$1

# True while PID is still our daemon NAME.  Zombies count as gone: where PID 1
# does not reap (some containers), a killed daemon lingers as <defunct>.
ours() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 1
  [[ $stat == "$1 ($2) "* && $stat != "$1 ($2) Z"* ]]
}

stop() {
  local name=$1 pidfile=$DIR/$1.pid pid
  [[ -s $pidfile ]] || return 0
  pid=$(<"$pidfile")
  # The name check guards against a PID recycled since the daemon died.
  if [[ $pid =~ ^[0-9]+$ ]] && ours "$pid" "$name"; then
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 50); do ours "$pid" "$name" || break; sleep 0.1; done
    if ours "$pid" "$name"; then kill -9 "$pid" 2>/dev/null || true; fi
  fi
  rm -f "$pidfile"
}

# slurmd first so it does not retry a vanished slurmctld; munged last because
# both daemons still authenticate while shutting down.
stop slurmd
stop slurmctld
stop munged
