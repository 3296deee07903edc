#include "jobs/ground_sweep.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <optional>

#include "core/stage_log.hpp"
#include "io/ground_bank.hpp"
#include "jobs/command.hpp"
#include "jobs/ground_job.hpp"
#include "jobs/run_options.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {
namespace {

// The config as job_config() loads it, except that without -c/--config the built-in
// configs/ground-demo.toml comes first (the schema's defaults are the full grid, a cluster job).
std::optional<io::Config> ground_config(MPI_Comm world, const JobOptions& options) {
  if (!options.config_path.empty()) return job_config(world, ground_schema(), options);
  io::Config config(ground_schema());
  mpi::agree(world, [&] {
    config.merge_toml(builtin_ground_demo_toml(), kBuiltinGroundDemoSource);
    for (const auto& s : options.sets) config.set(s);
  });
  if (!options.print_config) return config;
  if (mpi::rank(world) == 0) std::fputs(config.to_toml().c_str(), stdout);
  return std::nullopt;
}

}  // namespace

BankSweep ground_bank_sweep(const io::Config& config) {
  const auto spec = std::make_shared<const GroundSpec>(make_ground_spec(config));
  const auto tasks = std::make_shared<const std::vector<GroundTask>>(ground_tasks(*spec));
  BankSweep sweep;
  sweep.kind = "ground";
  sweep.config_toml = ground_sweep_toml(config, *spec);
  std::string names;
  for (const auto& m : spec->materials) names += (names.empty() ? "" : ", ") + m.name;
  sweep.summary = fmt::format("{} grounds ({}) x {} elevations = {} tasks; {} etas in [{}, {}], {} samples per eta; "
                              "air c0 = {} m/s", spec->materials.size(), names, spec->elevation_rad.size(), tasks->size(),
                              spec->eta.size(), spec->eta.front(), spec->eta.back(), spec->samples_per_eta, spec->c0_m_s);
  for (const auto& t : *tasks) sweep.task_names.push_back(t.name);
  sweep.run_task = [spec, tasks](MPI_Comm group, std::size_t t) { return run_ground_task(group, *spec, (*tasks)[t]); };
  sweep.merge = [spec, config_toml = sweep.config_toml](const std::string& results_dir) {
    auto bank = std::make_shared<const model::GroundBank>(merge_ground_results(*spec, results_dir, config_toml));
    return MergedBank{bank->sweep, [bank, config_toml](const std::string& out, const std::string& command, int n_ranks) {
                        io::write_ground_bank(out, *bank, command, config_toml, n_ranks);
                      }};
  };
  return sweep;
}

Command add_ground_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("ground", "build a ground bank: the regularized Lamb's problem radiated into the air "
                                              "over (material, elevation, eta) (docs/ground.md, docs/bank-format.md)");
  auto options = std::make_shared<JobOptions>();
  auto sweep = std::make_shared<BankSweepOptions>();
  options->out = "ground.h5";
  add_job_options(*app, *options, "output ground bank", true);
  add_sweep_options(*app, *sweep);
  return {app, [options, sweep](const JobContext& context) -> int {
            const auto config = ground_config(context.world, *options);
            if (!config) return kExitOk;
            Stage stage("ground");
            sweep->out = options->out;
            sweep->progress_interval_s = options->progress_interval_s;
            sweep->command = context.command_line;
            BankSweep bank;
            mpi::agree(context.world, [&] { bank = ground_bank_sweep(*config); });
            return run_bank_sweep(context.world, bank, *sweep);
          }};
}

}  // namespace clatter::jobs
