#include "jobs/pan_sweep.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <filesystem>
#include <memory>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/stage_log.hpp"
#include "io/pan_bank.hpp"
#include "jobs/command.hpp"
#include "jobs/output_guard.hpp"
#include "jobs/pan_job.hpp"
#include "jobs/run_options.hpp"
#include "jobs/sweep.hpp"
#include "kernels/pan/directions.hpp"
#include "mpi/comm.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

void parse_slice(const std::string& text, SweepOptions& o) {
  if (text.empty()) return;
  char slash = 0;
  std::size_t used = 0;
  try {
    o.slice_index = std::stoi(text, &used);
    slash = used < text.size() ? text[used] : 0;
    o.slice_count = std::stoi(text.substr(used + 1));
  } catch (const std::exception&) {
    slash = 0;
  }
  if (slash != '/' || o.slice_count < 1 || o.slice_index < 0 || o.slice_index >= o.slice_count)
    throw InputError(fmt::format("--slice '{}': expected K/N with 0 <= K < N (e.g. $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)", text));
}

// Rank 0 merges and writes, unless that would lose a bank already at `out`; every rank learns the
// outcome.
int merge_and_write(MPI_Comm world, const SweepLocks& locks, const PanSpec& spec, const std::string& results_dir,
                    const std::string& config_toml, const std::string& out, const std::string& command, bool force) {
  int code = kExitOk;
  mpi::agree(world, [&] {
    if (mpi::rank(world) != 0) return;
    Stage stage("merge");
    const model::PanBank bank = merge_pan_results(spec, results_dir, config_toml);
    check_replace(out, bank.sweep, force);
    locks.check_held();
    io::write_pan_bank(out, bank, command, config_toml, mpi::size(world));
    spdlog::info("merge: wrote {} ({} of {} tasks; {} failed, {} missing)", out,
                 bank.sweep.tasks_done(), bank.sweep.tasks_total,
                 bank.sweep.failed.size(), bank.sweep.missing.size());
    for (const auto& f : bank.sweep.failed) spdlog::error("merge: failed: {}", f);
    if (!bank.sweep.missing.empty())
      spdlog::warn("merge: {} task(s) missing, e.g. {}", bank.sweep.missing.size(), bank.sweep.missing.front());
    if (!bank.sweep.failed.empty() || !bank.sweep.missing.empty()) code = kExitTasksFailed;
  });
  mpi::check(MPI_Bcast(&code, 1, MPI_INT, 0, world), "MPI_Bcast");
  return code;
}

}  // namespace

int run_pan_sweep(MPI_Comm world, const io::Config& config, const PanSweepOptions& options) {
  PanSpec spec;
  SweepOptions so;
  mpi::agree(world, [&] {
    spec = make_pan_spec(config);
    parse_slice(options.slice, so);
  });
  so.results_dir = options.results.empty() ? options.out + ".tasks" : options.results;
  so.ranks_per_task = options.ranks_per_task;
  so.resume = options.resume;
  so.progress_interval_s = options.progress_interval_s;
  const std::string config_toml = config.to_toml();
  const auto tasks = pan_tasks(spec);
  std::vector<std::string> names;
  for (const auto& t : tasks) names.push_back(t.name);
  spdlog::info("pan: {} proxies x {} fields = {} tasks; {} directions x {} radii, N = {}, epsilon = {}",
               spec.proxies_bc_m.size(), spec.solve.fields.size(), tasks.size(), kernels::pan::vertex_count(spec.divisions),
               spec.radii_m.size(), spec.terms, spec.epsilon);
  // Before the results folder or the output is touched; held until this function returns.
  const SweepLocks locks(world, so.results_dir, so.slice_index, so.slice_count, so.slice_count > 1 ? "" : options.out,
                         options.command);
  if (so.slice_count == 1)  // a bank at OUT that the merge would keep is kept before anything is computed
    mpi::agree(world, [&] {
      if (mpi::rank(world) == 0)
        check_replace(options.out, {io::sweep_id(config_toml), static_cast<std::uint32_t>(tasks.size()), {}, {}},
                      options.force);
    });
  SweepReport report;
  {
    Stage stage("sweep");
    report = run_sweep(world, locks, names, config_toml, so, [&](MPI_Comm group, std::size_t t) {
      return run_pan_task(group, spec, tasks[t], options.progress_interval_s);
    });
  }
  const bool root = mpi::rank(world) == 0;
  if (report.interrupted) {
    if (root)
      spdlog::warn("pan: interrupted by signal {}: {} task(s) finished in this run are kept in {}; resume with:\n  {}{}",
                   interrupt_signal(), report.done_now + report.failed, so.results_dir, options.command,
                   options.resume ? "" : " --resume");
    return kExitInterrupted;
  }
  if (so.slice_count > 1) {
    if (root)
      spdlog::info("pan: slice {}/{} finished ({} done, {} failed); when every slice has, run: clatter-bank merge "
                   "--results {} --out {}",
                   so.slice_index, so.slice_count, report.done_now, report.failed, so.results_dir, options.out);
    return report.failed > 0 ? kExitTasksFailed : kExitOk;
  }
  const int code =
      merge_and_write(world, locks, spec, so.results_dir, config_toml, options.out, options.command, options.force);
  if (code == kExitOk && !options.keep_results && root) {
    std::error_code ec;  // the bank holds everything now
    fs::remove_all(so.results_dir, ec);
    if (ec) spdlog::warn("pan: could not remove {}: {}", so.results_dir, ec.message());
  }
  return code;
}

int run_pan_merge(MPI_Comm world, const std::string& results_dir, const std::string& out, const std::string& command,
                  bool force) {
  const SweepLocks locks(world, results_dir, 0, 1, out, command);
  std::string config_toml;
  PanSpec spec;
  mpi::agree(world, [&] {
    config_toml = read_sweep_config(results_dir);
    io::Config config(pan_schema());
    config.merge_toml(config_toml, (fs::path(results_dir) / "sweep.toml").string());
    spec = make_pan_spec(config);
  });
  return merge_and_write(world, locks, spec, results_dir, config_toml, out, command, force);
}

Command add_pan_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("pan", "build a PAN proxy bank: FDTD solves over the (B, C) proxies, wavelet fit, "
                                           "compression (docs/bank-format.md)");
  auto options = std::make_shared<JobOptions>();
  auto sweep = std::make_shared<PanSweepOptions>();
  options->out = "bank.h5";
  add_job_options(*app, *options, "output PAN bank", true);
  app->add_option("--results", sweep->results, "folder of per-task result files (default: OUT.tasks)");
  app->add_option("--ranks-per-task", sweep->ranks_per_task, "MPI ranks that solve one task together (divides the "
                                                             "rank count)")
      ->capture_default_str();
  app->add_flag("--resume", sweep->resume, "keep the verified finished tasks in --results and do the rest");
  app->add_option("--slice", sweep->slice, "K/N: only tasks t with t % N == K, no merge (Slurm job arrays)");
  app->add_flag("--keep-results", sweep->keep_results, "keep the task files after a complete merge");
  app->add_flag("--force", sweep->force, "replace the bank at OUT even if it holds more of this sweep or another sweep");
  return {app, [options, sweep](const JobContext& context) -> int {
            const auto config = job_config(context.world, pan_schema(), *options);
            if (!config) return kExitOk;
            Stage stage("pan");
            sweep->out = options->out;
            sweep->progress_interval_s = options->progress_interval_s;
            sweep->command = context.command_line;
            return run_pan_sweep(context.world, *config, *sweep);
          }};
}

Command add_merge_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("merge", "merge a sweep's results folder into a PAN bank (after job array slices)");
  auto results = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>("bank.h5");
  auto force = std::make_shared<bool>(false);
  app->add_option("--results", *results, "the sweep's results folder")->required();
  app->add_option("-o,--out", *out, "output PAN bank")->capture_default_str();
  app->add_flag("--force", *force, "replace the bank at OUT even if it holds more of this sweep or another sweep");
  return {app, [results, out, force](const JobContext& context) -> int {
            Stage stage("merge");
            return run_pan_merge(context.world, *results, *out, context.command_line, *force);
          }};
}

}  // namespace clatter::jobs
