// clatter-bank: the MPI driver that builds Clatter's soundbanks. The subcommands come from the
// bank kinds of the registry and banks/commands.hpp; this file only parses and dispatches.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <vector>

#include "io/linked_libraries.hpp"
#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "banks/commands.hpp"
#include "cli/run_options.hpp"
#include "petsc/session.hpp"
#include "mpi/comm.hpp"
#include "mpi/log.hpp"
#include "mpi/session.hpp"
#include "mpi/stage_report.hpp"

namespace {

using namespace clatter;

int bank_main(mpi::Session& session, int argc, char** argv) {
  const MPI_Comm world = session.world();
  CLI::App app{"clatter-bank: builds Clatter soundbanks on MPI ranks.\n"
               "Run under mpirun/srun for more than one rank. Exit codes: 0 done, 1 run-time failure, 2 bad input,\n"
               "3 interrupted (SIGTERM/SIGINT; run again with --resume), 4 some sweep tasks failed.",
               "clatter-bank"};
  // The modal bank's solvers too (run-time versions; no PETSc initialization needed to ask).
  app.set_version_flag("--version", io::version_text("clatter-bank") + "  solvers:  " + petsc::Session::versions() +
                                         " (MUMPS through PETSc)");
  app.require_subcommand(1);
  app.fallthrough();  // global options may follow the subcommand
  jobs::GlobalOptions global;
  jobs::add_global_options(app, global);
  const std::vector<jobs::Command> commands = jobs::add_commands(app);

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

  const jobs::RunContext context{world, session.is_root(), session.size(), jobs::command_line(argc, argv),
                                 global.progress_interval_s};
  int code = kExitOk;
  for (const auto& command : commands)
    if (command.app->parsed()) code = command.run(context);

  if (global.log_view) {
    auto table = mpi::stage_table(world, stage_log());
    if (session.is_root()) std::fputs(("\n" + table).c_str(), stdout);
  }
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  return clatter::mpi::run(argc, argv, "clatter-bank",
                           [&](clatter::mpi::Session& session) { return bank_main(session, argc, argv); });
}
