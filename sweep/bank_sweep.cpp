#include "sweep/bank_sweep.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/stage_log.hpp"
#include "io/sweep_files.hpp"
#include "mpi/collectives.hpp"
#include "sweep/output_guard.hpp"
#include "mpi/comm.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

// Rank 0 merges and writes, unless that would lose a bank already at `out`; every rank learns the
// outcome.
int merge_and_write(MPI_Comm world, const SweepLocks& locks, const BankSweep& sweep, const std::string& results_dir,
                    const std::string& out, const std::string& command, bool force) {
  int code = kExitOk;
  mpi::agree(world, [&] {
    if (mpi::rank(world) != 0) return;
    Stage stage("merge");
    const MergedBank bank = sweep.merge(results_dir);
    check_replace(out, bank.sweep, force);
    locks.check_held();
    bank.write(out, command, mpi::size(world));
    const auto& s = bank.sweep;
    spdlog::info("merge: wrote {} ({} of {} tasks; {} failed, {} missing)", out, s.tasks_done(), s.tasks_total,
                 s.failed.size(), s.missing.size());
    for (const auto& f : s.failed) spdlog::error("merge: failed: {}", f);
    if (!s.missing.empty()) spdlog::warn("merge: {} task(s) missing, e.g. {}", s.missing.size(), s.missing.front());
    if (!s.complete()) code = kExitTasksFailed;
  });
  return mpi::broadcast(world, code);
}

}  // namespace

void add_sweep_options(CLI::App& app, SweepOptions& o) {
  app.add_option("--results", o.results, "folder of per-task result files (default: OUT.tasks)");
  app.add_option("--ranks-per-task", o.ranks_per_task, "MPI ranks that solve one task together (divides the rank count)")
      ->capture_default_str();
  app.add_flag("--resume", o.resume, "keep the verified finished tasks in --results and do the rest");
  app.add_option("--slice", o.slice, "K/N: only tasks t with t % N == K, no merge (Slurm job arrays)");
  app.add_flag("--keep-results", o.keep_results, "keep the task files after a complete merge");
  app.add_flag("--force", o.force, "replace the bank at OUT even if it holds more of this sweep or another sweep");
}

int run_bank_sweep(MPI_Comm world, const BankSweep& sweep, const SweepOptions& options, const std::string& command) {
  Slice slice;
  mpi::agree(world, [&] { slice = parse_slice(options.slice); });
  const std::string& kind = sweep.manifest.kind;
  spdlog::info("{}: {}", kind, sweep.summary);
  const std::string results_dir = options.results_dir();
  // Before the results folder or the output is touched; held until this function returns.
  const SweepLocks locks(world, results_dir, slice.index, slice.count, slice.count > 1 ? "" : options.out, command);
  // A resumed run whose bank is already whole: its task files went when it was merged, and solving
  // them again would only rewrite the same bank.
  if (slice.count == 1 && options.resume) {
    bool done = false;
    mpi::agree(world, [&] {
      if (mpi::rank(world) == 0) done = holds_complete_bank(options.out, sweep.manifest.id());
    });
    if (mpi::broadcast(world, done)) {
      spdlog::info("{}: {} already holds every task of this sweep; nothing to resume (leave out --resume to "
                   "build it again)",
                   kind, options.out);
      return kExitOk;
    }
  }
  if (slice.count == 1)  // a bank at OUT that the merge would keep is kept before anything is computed
    mpi::agree(world, [&] {
      if (mpi::rank(world) == 0)
        check_replace(options.out,
                      {sweep.manifest.id(), static_cast<std::uint32_t>(sweep.task_names.size()), {}, {}},
                      options.force);
    });
  SweepReport report;
  {
    Stage stage("sweep");
    report = run_sweep(world, locks, sweep.manifest, sweep.task_names, options, slice, sweep.run_task);
  }
  const bool root = mpi::rank(world) == 0;
  if (report.interrupted) {
    if (root)
      spdlog::warn("{}: interrupted by signal {}: {} task(s) finished in this run are kept in {}; resume with:\n  {}{}",
                   kind, interrupt_signal(), report.done_now + report.failed, results_dir, command,
                   options.resume ? "" : " --resume");
    return kExitInterrupted;
  }
  if (slice.count > 1) {
    if (root)
      spdlog::info("{}: slice {}/{} finished ({} done, {} failed); when every slice has, run: clatter-bank merge "
                   "--results {} --out {}",
                   kind, slice.index, slice.count, report.done_now, report.failed, results_dir, options.out);
    return report.failed > 0 ? kExitTasksFailed : kExitOk;
  }
  const int code = merge_and_write(world, locks, sweep, results_dir, options.out, command, options.force);
  if (code == kExitOk && !options.keep_results && root) {
    std::error_code ec;  // the bank holds everything now
    fs::remove_all(results_dir, ec);
    if (ec) spdlog::warn("{}: could not remove {}: {}", kind, results_dir, ec.message());
  }
  return code;
}

int run_bank_merge(MPI_Comm world, const BankSweep& sweep, const std::string& results_dir, const std::string& out,
                   const std::string& command, bool force) {
  const SweepLocks locks(world, results_dir, 0, 1, out, command);
  return merge_and_write(world, locks, sweep, results_dir, out, command, force);
}

}  // namespace clatter::jobs
