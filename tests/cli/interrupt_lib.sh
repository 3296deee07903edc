# Sourced by the sweep tests (sweep_checks.sh, modal_checks.sh): SIGTERM to a sweep's ranks once
# its first task file has landed.
# Only this sweep's ranks: the clatter-bank processes below the launcher (a subshell, then
# mpiexec), never those of tests running beside this one.
descendants() { local c; for c in $(pgrep -P "$1"); do echo "$c"; descendants "$c"; done; }
# term_ranks_when LAUNCHER_PID GLOB: waits up to 60 s for a file matching GLOB, then sends SIGTERM
# to the launcher's clatter-bank ranks; returns 1 when no file landed and it found none to signal
# (returns 0 without signalling when the sweep's ranks had already ended after a file landed).
term_ranks_when() {
  local launcher=$1 glob=$2 ranks landed=0
  for _ in $(seq 1200); do
    compgen -G "$glob" > /dev/null && landed=1 && break
    sleep 0.05
  done
  ranks=$(for p in $(descendants "$launcher"); do [[ $(ps -o comm= -p "$p") == clatter-bank ]] && echo "$p"; done)
  # No rank left after the first task landed: a short sweep finished its last tasks first (seen
  # on a quiet machine); the caller's wait gets its exit code and takes the finished branch.
  [[ -n $ranks ]] || return $((1 - landed))
  # shellcheck disable=SC2086
  kill -TERM $ranks
}
