#include "jobs/pan_sweep.hpp"

#include <fmt/format.h>

#include <memory>

#include "core/stage_log.hpp"
#include "io/pan_bank.hpp"
#include "jobs/command.hpp"
#include "jobs/pan_job.hpp"
#include "jobs/run_options.hpp"
#include "kernels/pan/directions.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {

BankSweep pan_bank_sweep(const io::Config& config, double progress_interval_s) {
  const auto spec = std::make_shared<const PanSpec>(make_pan_spec(config));
  const auto tasks = std::make_shared<const std::vector<PanTask>>(pan_tasks(*spec));
  BankSweep sweep;
  sweep.kind = "pan";
  sweep.config_toml = config.to_toml();
  sweep.summary = fmt::format("{} proxies x {} fields = {} tasks; {} directions x {} radii, N = {}, epsilon = {}",
                              spec->proxies_bc_m.size(), spec->solve.fields.size(), tasks->size(),
                              kernels::pan::vertex_count(spec->divisions), spec->radii_m.size(), spec->terms,
                              spec->epsilon);
  for (const auto& t : *tasks) sweep.task_names.push_back(t.name);
  sweep.run_task = [spec, tasks, progress_interval_s](MPI_Comm group, std::size_t t) {
    return run_pan_task(group, *spec, (*tasks)[t], progress_interval_s);
  };
  sweep.merge = [spec, config_toml = sweep.config_toml](const std::string& results_dir) {
    auto bank = std::make_shared<const model::PanBank>(merge_pan_results(*spec, results_dir, config_toml));
    return MergedBank{bank->sweep, [bank, config_toml](const std::string& out, const std::string& command, int n_ranks) {
                        io::write_pan_bank(out, *bank, command, config_toml, n_ranks);
                      }};
  };
  return sweep;
}

Command add_pan_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("pan", "build a PAN proxy bank: FDTD solves over the (B, C) proxies, wavelet fit, "
                                           "compression (docs/bank-format.md)");
  auto options = std::make_shared<JobOptions>();
  auto sweep = std::make_shared<BankSweepOptions>();
  options->out = "bank.h5";
  add_job_options(*app, *options, "output PAN bank", true);
  add_sweep_options(*app, *sweep);
  return {app, [options, sweep](const JobContext& context) -> int {
            const auto config = job_config(context.world, pan_schema(), *options);
            if (!config) return kExitOk;
            Stage stage("pan");
            sweep->out = options->out;
            sweep->progress_interval_s = options->progress_interval_s;
            sweep->command = context.command_line;
            BankSweep bank;
            mpi::agree(context.world, [&] { bank = pan_bank_sweep(*config, options->progress_interval_s); });
            return run_bank_sweep(context.world, bank, *sweep);
          }};
}

}  // namespace clatter::jobs
