#!/usr/bin/env bash
# The sweep on a real Slurm (private, single node, started and stopped here): the sbatch script
# that `clatter-bank plan --sbatch` writes, and a job array + merge job (--dependency=afterok),
# must give banks whose content hash equals a direct `mpiexec -n 2` run's; and of two jobs
# submitted on one output, exactly one writes it.
# Usage: slurm_sweep.sh CLATTER_BANK CONFIG SCRATCH MPIEXEC...
set -uo pipefail
bank=$1 config=$2 scratch=$3
shift 3
mpiexec=("$@")
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() {
  echo "FAIL: $*"
  [[ -n ${holder:-} ]] && kill -CONT "$holder" 2> /dev/null  # a stopped rank must not outlive the test
  for f in clatter-pan*.out; do [[ -e $f ]] && { echo "== $f"; tail -20 "$f"; }; done
  if [[ -n ${SLURM_CONF:-} ]]; then  # what Slurm thought, while it still runs
    [[ -f queue.log ]] && { echo "== queue states polled (count, seconds, state)"; uniq -c -f1 queue.log | tail -20; }
    echo "== squeue"; squeue -a -o '%i %T %r %S' 2>&1
    echo "== sinfo"; sinfo -N -o '%N %T %E' 2>&1
    echo "== slurmctld.log"; tail -25 "$cluster/slurmctld.log"
  fi
  exit 1
}
cluster="$scratch/cluster"
trap 'bash "$here/slurm-down.sh" "$cluster" > /dev/null 2>&1' EXIT  # also when a check fails
bash "$here/slurm-up.sh" "$cluster" > up.log 2>&1 || { cat up.log; fail "could not start the private Slurm"; }
# shellcheck disable=SC1091
source "$cluster/env.sh"
echo "Slurm up: $(sinfo -h -o '%N %C %T')"

sets=(--set 'proxies.list_m=[[0.5, 0.5], [0.35, 0.2]]' --set 'solve.fields=[1, 4, 6]')
sum() { "$bank" checksum "$1" | cut -d' ' -f1; }
"${mpiexec[@]}" -n 2 "$bank" pan -c "$config" "${sets[@]}" -o direct.h5 > direct.log 2>&1 || fail "direct run: $(tail -3 direct.log)"
echo "direct mpiexec -n 2:        $(sum direct.h5)"

# One MPI job, as plan writes it.
"$bank" plan -c "$config" "${sets[@]}" --ranks 2 --cores-per-node "$(getconf _NPROCESSORS_ONLN)" -o one.h5 --sbatch one.sbatch > plan.log 2>&1 || fail "plan: $(cat plan.log)"
timeout 300 sbatch --wait one.sbatch > submit.log 2>&1 || fail "sbatch one.sbatch: $(cat submit.log)"
[[ -f one.h5 ]] || fail "the batch job wrote no bank"
echo "sbatch (plan --sbatch):     $(sum one.h5)"

# A job array of 2 slices, then the merge job once both succeeded.
"$bank" plan -c "$config" "${sets[@]}" --ranks 2 --cores-per-node "$(getconf _NPROCESSORS_ONLN)" -o array.h5 --sbatch array.sbatch --array 2 > plan-array.log 2>&1 ||
  fail "plan --array: $(cat plan-array.log)"
jid=$(sbatch --parsable array.sbatch) || fail "sbatch array.sbatch"
timeout 300 sbatch --wait --dependency="afterok:${jid%%;*}" array.sbatch.merge > merge.log 2>&1 || fail "merge job: $(cat merge.log)"
[[ -f array.h5 ]] || fail "the merge job wrote no bank"
echo "job array of 2 + merge:     $(sum array.h5)"

# The time-limit warning: SIGTERM to the job's ranks (what --signal=TERM@120 sends) once the
# first task has landed. The ranks stop cleanly, the script requeues the job, and the second start
# resumes where the first stopped.
"$bank" plan -c "$config" "${sets[@]}" --set grid.dx_m=0.02 --set time.dt_s=3.3e-5 --ranks 2 \
  --cores-per-node "$(getconf _NPROCESSORS_ONLN)" -o requeue.h5 --sbatch requeue.sbatch > plan-requeue.log 2>&1 ||
  fail "plan: $(cat plan-requeue.log)"
"${mpiexec[@]}" -n 2 "$bank" pan -c requeue.sbatch.toml -o requeue-direct.h5 > requeue-direct.log 2>&1 || fail "direct run"
jid=$(sbatch --parsable requeue.sbatch) || fail "sbatch requeue.sbatch"
for _ in $(seq 1200); do
  compgen -G 'requeue.h5.tasks/p*.h5' > /dev/null && break
  sleep 0.05
done
scancel --signal=TERM "${jid%%;*}" || fail "scancel --signal=TERM"
# Until the requeued start has written the bank (the job leaves the queue for a moment while it
# is requeued, so its absence proves nothing).
# Slurm holds a requeued job back for 2 minutes (StartTime = requeue + 121 s); a test need not
# wait that long. But slurmd revokes the first start's credential (in whole seconds), and a
# restart within the second of that revocation can fail to launch, which holds the job for good
# ("launch failed requeued held"; the likely cause of a CI failure that nudged to `now`). So move
# the start time only once the node is idle again, and to 2 s from then.
for _ in $(seq 480); do
  [[ -f requeue.h5 ]] && break
  state=$(squeue -h -j "${jid%%;*}" -o '%T %r %S' 2>/dev/null)
  node=$(sinfo -h -N -o %t 2>/dev/null)
  echo "$SECONDS $state node $node" >> queue.log
  start=${state##* }
  if [[ $state == PENDING\ BeginTime* && $node == idle && $start == 20* ]] &&
    (($(date -d "$start" +%s) > $(date +%s) + 5)); then
    scontrol update JobId="${jid%%;*}" StartTime=now+2 >> queue.log 2>&1
  fi
  [[ $state == *held* || $state == *Held* ]] && fail "the requeued job is held: $state"
  sleep 0.5
done
for _ in $(seq 60); do  # and until its output file is complete
  squeue -h -j "${jid%%;*}" 2>/dev/null | grep -q . || break
  sleep 0.5
done
[[ -f requeue.h5 ]] || fail "the requeued job did not finish the bank"
grep -q "interrupted (exit 3), requeueing" clatter-pan-"${jid%%;*}".out || fail "the job was not interrupted cleanly"
grep -q "already done" clatter-pan-"${jid%%;*}".out || fail "the requeued job did not resume"
grep "interrupted by signal\|already done" clatter-pan-"${jid%%;*}".out | sed 's/^/  /'
echo "SIGTERM, requeue, resume:   $(sum requeue.h5) (direct: $(sum requeue-direct.h5))"
[[ $(sum requeue.h5) == "$(sum requeue-direct.h5)" ]] || fail "the requeued bank differs from the direct run"

# Two jobs submitted on one output (a double submission): 1 rank each, so both fit the node at
# once. The first job's rank is stopped once it holds the lock, so the second surely meets a live
# holder; it must exit 2 naming it and compute nothing, and the first then finishes the bank.
"$bank" plan -c requeue.sbatch.toml --ranks 1 --cores-per-node "$(getconf _NPROCESSORS_ONLN)" -o twice.h5 \
  --sbatch twice.sbatch > plan-twice.log 2>&1 || fail "plan: $(cat plan-twice.log)"
jid1=$(sbatch --parsable twice.sbatch) || fail "sbatch twice.sbatch (first)"
for _ in $(seq 1200); do
  [[ -e twice.h5.tasks.lock ]] && break
  sleep 0.05
done
holder=$(sed -n 's/^pid=//p' twice.h5.tasks.lock)
[[ -n $holder ]] || fail "the first job took no lock"
kill -STOP "$holder"
jid2=$(sbatch --parsable twice.sbatch) || fail "sbatch twice.sbatch (second)"
for _ in $(seq 600); do
  squeue -h -j "$jid2" 2>/dev/null | grep -q . || break
  sleep 0.5
done
kill -CONT "$holder"
for _ in $(seq 600); do
  squeue -h -j "$jid1" 2>/dev/null | grep -q . || break
  sleep 0.5
done
second=clatter-pan-$jid2.out
grep -q "locked by host $(hostname), PID $holder, since" "$second" || fail "the second job did not name the holder"
grep -q "solve:" "$second" && fail "the second job computed while the first held the output"
exit2=$(scontrol show job "$jid2" 2>/dev/null | grep -o 'ExitCode=[0-9]*' | head -1)
[[ -z $exit2 || $exit2 == ExitCode=2 ]] || fail "the second job: $exit2, expected 2"
[[ -f twice.h5 ]] || fail "the first job wrote no bank"
echo "two jobs on one output:     $(sum twice.h5) (second job ${exit2:-ExitCode=?}: $(grep -o 'locked by host.*since [0-9TZ:-]*' "$second"))"
[[ $(sum twice.h5) == "$(sum requeue-direct.h5)" ]] || fail "the bank of the two jobs differs from the direct run"

ref=$(sum direct.h5)
[[ $(sum one.h5) == "$ref" && $(sum array.h5) == "$ref" ]] || fail "a Slurm bank differs from the direct run"
echo "Slurm banks equal the direct run: $ref"
