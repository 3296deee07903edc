#include "jobs/modal_sweep.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>

#include "core/stage_log.hpp"
#include "io/modal_bank.hpp"
#include "jobs/command.hpp"
#include "jobs/modal_job.hpp"
#include "jobs/run_options.hpp"
#include "mpi/comm.hpp"
#include "petsc/session.hpp"

namespace clatter::jobs {

BankSweep modal_bank_sweep(const io::Config& config) {
  ModalSpec made = make_modal_spec(config);
  made.header.solver_libraries = petsc::Session::versions();
  const auto spec = std::make_shared<const ModalSpec>(std::move(made));
  const auto tasks = std::make_shared<const std::vector<ModalTask>>(modal_tasks(*spec));
  BankSweep sweep;
  sweep.kind = "modal";
  sweep.config_toml = modal_sweep_toml(config, *spec);
  const auto& m = spec->header.material;
  sweep.summary = fmt::format("{} ellipsoids of {} (E = {:.4g} Pa, nu = {}, rho = {} kg/m^3); modes to {} f_1; {} with MUMPS",
                              tasks->size(), m.name, m.youngs_pa, m.poisson, m.rho_kg_m3, spec->header.f_max_multiple,
                              spec->header.solver_libraries);
  for (const auto& t : *tasks) sweep.task_names.push_back(t.name);
  sweep.run_task = [spec, tasks](MPI_Comm group, std::size_t t) { return run_modal_task(group, *spec, (*tasks)[t]); };
  sweep.merge = [spec, config_toml = sweep.config_toml](const std::string& results_dir) {
    auto bank = std::make_shared<const model::ModalBank>(merge_modal_results(*spec, results_dir, config_toml));
    return MergedBank{bank->sweep, [bank, config_toml](const std::string& out, const std::string& command, int n_ranks) {
                        io::write_modal_bank(out, *bank, command, config_toml, n_ranks);
                      }};
  };
  return sweep;
}

Command add_modal_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("modal", "build a modal bank: FEM modes of the normalized ellipsoids of the patch, "
                                             "SLEPc spectrum slicing (docs/modal.md, docs/bank-format.md)");
  auto options = std::make_shared<JobOptions>();
  auto sweep = std::make_shared<BankSweepOptions>();
  options->out = "modal.h5";
  add_job_options(*app, *options, "output modal bank", true);
  add_sweep_options(*app, *sweep);
  return {app, [options, sweep](const JobContext& context) -> int {
            const auto config = job_config(context.world, modal_schema(), *options);
            if (!config) return kExitOk;
            Stage stage("modal");
            sweep->out = options->out;
            sweep->progress_interval_s = options->progress_interval_s;
            sweep->command = context.command_line;
            BankSweep bank;
            mpi::agree(context.world, [&] { bank = modal_bank_sweep(*config); });
            const petsc::Session petsc(context.world);
            if (context.is_root && !petsc.ignored_environment().empty())
              spdlog::warn("modal: ignored (solver settings come from the config only): {}", petsc.ignored_environment());
            return run_bank_sweep(context.world, bank, *sweep);
          }};
}

}  // namespace clatter::jobs
