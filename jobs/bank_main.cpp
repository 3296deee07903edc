// clatter-bank: the MPI driver that builds Clatter's soundbanks. One subcommand per job.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <optional>

#include "core/build_info.hpp"
#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "jobs/field_job.hpp"
#include "jobs/run_options.hpp"
#include "jobs/solve_job.hpp"
#include "mpi/comm.hpp"
#include "mpi/log.hpp"
#include "mpi/session.hpp"
#include "mpi/stage_report.hpp"

namespace {

using namespace clatter;

int bank_main(mpi::Session& session, int argc, char** argv) {
  const MPI_Comm world = session.world();
  CLI::App app{"clatter-bank: builds Clatter soundbanks on MPI ranks.\n"
               "Run under mpirun/srun for more than one rank. Exit codes: 0 done, 1 run-time failure, 2 bad input.",
               "clatter-bank"};
  app.set_version_flag("--version", version_text("clatter-bank"));
  app.require_subcommand(1);
  app.fallthrough();  // global options may follow the subcommand
  jobs::GlobalOptions global;
  jobs::add_global_options(app, global);

  jobs::ConfigOptions field_config;
  std::string field_out = "field.h5";
  auto* field = app.add_subcommand("field", "sample the exact pressure of a psi-driven monopole on a distributed "
                                            "grid and write it with collective HDF5 (the foundation demo)");
  jobs::add_config_options(*field, field_config);
  field->add_option("-o,--out", field_out, "output HDF5 file")->capture_default_str();

  jobs::ConfigOptions solve_config;
  std::string solve_out = "raw.h5";
  double progress_interval_s = 10.0;
  auto* solve = app.add_subcommand("solve", "FDTD solves around one rigid ellipsoid for the chosen rigid-body "
                                            "fields, recorded at listener points");
  jobs::add_config_options(*solve, solve_config);
  solve->add_option("-o,--out", solve_out, "output HDF5 file of raw time series")->capture_default_str();
  solve->add_option("--progress-interval", progress_interval_s, "seconds between progress lines (0: none)")
      ->capture_default_str();

  // Every rank parses the same argv, so a usage error is the same everywhere.
  bool exit_now = false;
  mpi::agree(world, [&] {
    try {
      app.parse(argc, argv);
    } catch (const CLI::Success& e) {  // --help, --version
      if (session.is_root()) app.exit(e);
      exit_now = true;
    } catch (const CLI::ParseError& e) {
      throw InputError(std::string(e.what()) + " (see clatter-bank --help)");
    }
  });
  if (exit_now) return kExitOk;
  mpi::agree(world, [&] {
    mpi::configure_logging(session.rank(), session.size(), {global.log_all_ranks, global.log_level});
  });

  // The job's config, or nullopt when --print-config asked only to print it.
  auto config_for = [&](const io::Schema& schema, const jobs::ConfigOptions& options) -> std::optional<io::Config> {
    auto config = jobs::load_config(world, schema, options);
    if (!options.print) return config;
    if (session.is_root()) std::fputs(config.to_toml().c_str(), stdout);
    return std::nullopt;
  };

  if (field->parsed()) {
    auto config = config_for(jobs::field_schema(), field_config);
    if (!config) return kExitOk;
    Stage stage("field");
    jobs::run_field(world, *config, field_out, jobs::command_line(argc, argv));
  }

  if (solve->parsed()) {
    auto config = config_for(jobs::solve_schema(), solve_config);
    if (!config) return kExitOk;
    Stage stage("solve");
    jobs::SolveSpec spec;
    mpi::agree(world, [&] { spec = jobs::make_solve_spec(*config); });
    auto result = jobs::run_solve(world, spec, progress_interval_s);
    if (session.is_root()) {
      Stage write("write");
      jobs::write_raw(solve_out, spec, result, *config, jobs::command_line(argc, argv), session.size());
      spdlog::info("solve: wrote {}", solve_out);
    }
  }

  if (global.log_view) {
    auto table = mpi::stage_table(world, stage_log());
    if (session.is_root()) std::fputs(("\n" + table).c_str(), stdout);
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  return clatter::mpi::run(argc, argv, "clatter-bank",
                           [&](clatter::mpi::Session& session) { return bank_main(session, argc, argv); });
}
