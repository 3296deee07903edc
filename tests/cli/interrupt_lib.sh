# shellcheck shell=bash
# Sourced by the sweep tests (sweep_checks.sh, modal_checks.sh, ground_checks.sh): SIGTERM to a
# sweep's ranks once its first task file has landed, and the check that the sweep was interrupted.
# Only this sweep's ranks: the clatter-bank processes below the launcher (a subshell, then
# mpiexec), never those of tests running beside this one.
descendants() { local c; for c in $(pgrep -P "$1"); do echo "$c"; descendants "$c"; done; }
# bank_ranks LAUNCHER_PID: the clatter-bank processes below the launcher.
bank_ranks() { local p; for p in $(descendants "$1"); do [[ $(ps -o comm= -p "$p") == clatter-bank ]] && echo "$p"; done; }
# interrupt_sweep LAUNCHER_PID GLOB LOG: waits up to 60 s for a task file matching GLOB, sends
# SIGTERM to the launcher's clatter-bank ranks, waits for the launcher and requires exit 3
# (kExitInterrupted). Prints why and returns 1 when no task file landed, when no rank was left to
# signal, or when the sweep exited otherwise (0: it handed out its last task before the signal
# came). A sweep that ends before the signal is never a pass: the caller's sweep must be long
# enough after its first task (see each caller) that the signal always lands mid-sweep.
interrupt_sweep() {
  local launcher=$1 glob=$2 log=$3 ranks landed=0 code
  for _ in $(seq 1200); do
    compgen -G "$glob" > /dev/null && landed=1 && break
    sleep 0.05
  done
  ranks=$(bank_ranks "$launcher")
  if [[ -z $ranks ]]; then
    wait "$launcher"
    code=$?
    if [[ $landed -eq 0 ]]; then
      echo "interrupt: no task file matching $glob within 60 s and no rank to signal (exit $code): $(tail -3 "$log")"
    else
      echo "interrupt: the sweep ended (exit $code) before it could be signalled: too short to test an interruption"
    fi
    return 1
  fi
  # shellcheck disable=SC2086
  kill -TERM $ranks || echo "interrupt: some rank had ended before the signal"
  wait "$launcher"
  code=$?
  if [[ $code -ne 3 ]]; then
    echo "interrupt: exit $code after SIGTERM, expected 3 (interrupted)$([[ $code -eq 0 ]] && echo ': the sweep finished before it saw the signal, too short to test an interruption'): $(tail -3 "$log")"
    return 1
  fi
  grep -q "interrupted by signal 15" "$log" || { echo "interrupt: exit 3 but no 'interrupted by signal 15' in the log: $(tail -3 "$log")"; return 1; }
}
