// `clatter-bank merge`: a results folder into its bank, whatever the bank kind (after the slices
// of a job array, or to retry a merge).
#include <filesystem>
#include <memory>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "jobs/command.hpp"
#include "jobs/ground_spec.hpp"
#include "jobs/ground_sweep.hpp"
#include "jobs/modal_spec.hpp"
#include "jobs/modal_sweep.hpp"
#include "jobs/pan_spec.hpp"
#include "jobs/pan_sweep.hpp"
#include "mpi/comm.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

// The sweep that made `results_dir`, rebuilt from its sweep.toml. A rebuilt manifest that differs
// from the stored one (a materials table edited since) would merge under another sweep id.
BankSweep sweep_of_results(const std::string& results_dir) {
  const std::string stored = read_sweep_config(results_dir);
  const std::string source = (fs::path(results_dir) / "sweep.toml").string();
  const bool modal = is_modal_config(stored), ground = !modal && is_ground_config(stored);
  io::Config config(modal ? modal_schema() : ground ? ground_schema() : pan_schema());
  config.merge_toml(stored, source);
  BankSweep sweep = modal ? modal_bank_sweep(config) : ground ? ground_bank_sweep(config) : pan_bank_sweep(config, 10);
  if (sweep.config_toml != stored)
    throw InputError(source + ": the sweep's inputs changed since it started (for a modal or ground bank: a material's "
                              "entry in its table); merge with the inputs it was run with, or run the sweep again");
  return sweep;
}

}  // namespace

Command add_merge_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("merge", "merge a sweep's results folder into its bank (PAN, modal or ground; "
                                             "after job array slices)");
  auto results = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>("bank.h5");
  auto force = std::make_shared<bool>(false);
  app->add_option("--results", *results, "the sweep's results folder")->required();
  app->add_option("-o,--out", *out, "output bank")->capture_default_str();
  app->add_flag("--force", *force, "replace the bank at OUT even if it holds more of this sweep or another sweep");
  return {app, [results, out, force](const JobContext& context) -> int {
            Stage stage("merge");
            BankSweep sweep;
            mpi::agree(context.world, [&] { sweep = sweep_of_results(*results); });
            return run_bank_merge(context.world, sweep, *results, *out, context.command_line, *force);
          }};
}

}  // namespace clatter::jobs
