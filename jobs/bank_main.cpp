// clatter-bank: the MPI driver that builds Clatter's soundbanks. One subcommand per job.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>

#include "io/linked_libraries.hpp"
#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "jobs/field_job.hpp"
#include "jobs/run_options.hpp"
#include "jobs/solve_job.hpp"
#include "jobs/pan_job.hpp"
#include "jobs/pan_sweep.hpp"
#include "jobs/plan.hpp"
#include "io/content_hash.hpp"
#include "kernels/pan/directions.hpp"
#include "jobs/bank_tools.hpp"
#include "io/pan_bank.hpp"
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
  app.set_version_flag("--version", io::version_text("clatter-bank"));
  app.require_subcommand(1);
  app.fallthrough();  // global options may follow the subcommand
  jobs::GlobalOptions global;
  jobs::add_global_options(app, global);

  // A job subcommand: its config options, its output file and, for long jobs, progress lines.
  double progress_interval_s = 10.0;
  struct Job {
    CLI::App* app;
    jobs::ConfigOptions config;
    std::string out;
  };
  auto add_job = [&](Job& job, const char* name, const char* help, const char* out_help, bool progress) {
    job.app = app.add_subcommand(name, help);
    jobs::add_config_options(*job.app, job.config);
    job.app->add_option("-o,--out", job.out, out_help)->capture_default_str();
    if (progress)
      job.app->add_option("--progress-interval", progress_interval_s, "seconds between progress lines (0: none)")
          ->capture_default_str();
  };
  Job field{nullptr, {}, "field.h5"}, solve{nullptr, {}, "raw.h5"}, pan{nullptr, {}, "bank.h5"};
  add_job(field, "field", "sample the exact pressure of a psi-driven monopole on a distributed grid and write it "
                          "with collective HDF5 (the foundation demo)", "output HDF5 file", false);
  add_job(solve, "solve", "FDTD solves around one rigid ellipsoid for the chosen rigid-body fields, recorded at "
                          "listener points", "output HDF5 file of raw time series", true);
  add_job(pan, "pan", "build a PAN proxy bank: FDTD solves over the (B, C) proxies, wavelet fit, compression "
                      "(docs/bank-format.md)", "output PAN bank", true);

  jobs::PanSweepOptions sweep;
  pan.app->add_option("--results", sweep.results, "folder of per-task result files (default: OUT.tasks)");
  pan.app->add_option("--ranks-per-task", sweep.ranks_per_task, "MPI ranks that solve one task together (divides the "
                                                                 "rank count)")
      ->capture_default_str();
  pan.app->add_flag("--resume", sweep.resume, "keep the verified finished tasks in --results and do the rest");
  pan.app->add_option("--slice", sweep.slice, "K/N: only tasks t with t % N == K, no merge (Slurm job arrays)");
  pan.app->add_flag("--keep-results", sweep.keep_results, "keep the task files after a complete merge");

  Job plan{nullptr, {}, "bank.h5"};
  add_job(plan, "plan", "predict a PAN sweep's cost (tasks, cells x steps, memory per rank, wall time from a "
                        "calibration solve run here) and write Slurm batch scripts", "the bank the job will write", false);
  jobs::PlanOptions plan_opt;
  plan.app->add_option("--ranks", plan_opt.ranks, "MPI ranks of the job")->capture_default_str();
  plan.app->add_option("--ranks-per-task", plan_opt.ranks_per_task, "ranks per task")->capture_default_str();
  plan.app->add_option("--cores-per-node", plan_opt.cores_per_node, "cores per node (default: this machine's)");
  plan.app->add_option("--rate", plan_opt.rate, "cell-updates/s per rank instead of measuring (e.g. from a stage table)");
  plan.app->add_option("--results", plan_opt.results, "results folder of the job (default: OUT.tasks)");
  plan.app->add_option("--sbatch", plan_opt.sbatch, "write a ready sbatch script here");
  plan.app->add_option("--array", plan_opt.array, "with --sbatch: a job array of N elements and a merge job (FILE.merge)");

  std::string merge_results, merge_out = "bank.h5";
  auto* merge = app.add_subcommand("merge", "merge a sweep's results folder into a PAN bank (after job array slices)");
  merge->add_option("--results", merge_results, "the sweep's results folder")->required();
  merge->add_option("-o,--out", merge_out, "output PAN bank")->capture_default_str();

  std::string checksum_path;
  auto* checksum = app.add_subcommand("checksum", "print a content hash of a Clatter HDF5 file that leaves out "
                                                  "/provenance/run (who ran it, when, on how many ranks)");
  checksum->add_option("file", checksum_path, "HDF5 file")->required();

  std::string bank_path;
  auto* info = app.add_subcommand("info", "describe a PAN bank: proxies, fields, epsilon, size, provenance");
  info->add_option("bank", bank_path, "PAN bank file")->required();

  jobs::ProbeRequest probe_req;
  auto* probe = app.add_subcommand("probe", "print p_i(x, t) of one proxy from a PAN bank as t_s,p_Pa CSV");
  probe->add_option("bank", probe_req.bank_path, "PAN bank file")->required();
  probe->add_option("--proxy", probe_req.proxy_bc_m, "proxy semi-axes B,C [m]")->delimiter(',')->required();
  probe->add_option("--field", probe_req.field, "rigid-body field 1-6")->required();
  probe->add_option("--point", probe_req.point_m, "listener x,y,z [m], proxy centred on the origin")
      ->delimiter(',')
      ->required();
  probe->add_option("--rate", probe_req.rate_hz, "output sample rate [Hz]: reconstruct within 2x of it (Algorithm 1); "
                                                 "0: the bank's rate")
      ->capture_default_str();
  probe->add_option("--scale", probe_req.scale, "beta: the proxy scaled by beta (eq. 10)")->capture_default_str();
  probe->add_option("--interpolation", probe_req.interpolation,
                    "between directions: quadratic (default) or linear (the paper's)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, kernels::pan::Interpolation>{
          {"linear", kernels::pan::Interpolation::linear}, {"quadratic", kernels::pan::Interpolation::quadratic}}));

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

  int code = kExitOk;
  if (field.app->parsed()) {
    auto config = config_for(jobs::field_schema(), field.config);
    if (!config) return kExitOk;
    Stage stage("field");
    jobs::run_field(world, *config, field.out, jobs::command_line(argc, argv));
  }

  if (solve.app->parsed()) {
    auto config = config_for(jobs::solve_schema(), solve.config);
    if (!config) return kExitOk;
    Stage stage("solve");
    jobs::SolveSpec spec;
    mpi::agree(world, [&] { spec = jobs::make_solve_spec(*config); });
    auto result = jobs::run_solve(world, spec, progress_interval_s);
    if (session.is_root()) {
      Stage write("write");
      jobs::write_raw(solve.out, spec, result, *config, jobs::command_line(argc, argv), session.size());
      spdlog::info("solve: wrote {}", solve.out);
    }
  }

  if (pan.app->parsed()) {
    auto config = config_for(jobs::pan_schema(), pan.config);
    if (!config) return kExitOk;
    Stage stage("pan");
    sweep.out = pan.out;
    sweep.progress_interval_s = progress_interval_s;
    sweep.command = jobs::command_line(argc, argv);
    code = jobs::run_pan_sweep(world, *config, sweep);
  }

  if (plan.app->parsed()) {
    auto config = config_for(jobs::pan_schema(), plan.config);
    if (!config) return kExitOk;
    namespace fs = std::filesystem;
    plan_opt.config_path = plan.config.path.empty() ? "" : fs::absolute(plan.config.path).string();
    plan_opt.out = fs::absolute(plan.out).string();
    if (!plan_opt.results.empty()) plan_opt.results = fs::absolute(plan_opt.results).string();
    plan_opt.binary = fs::canonical("/proc/self/exe").string();
    std::string text;
    mpi::agree(world, [&] {
      if (session.is_root()) text = jobs::run_plan(*config, plan_opt);
    });
    if (session.is_root()) std::fputs(text.c_str(), stdout);
  }

  if (merge->parsed()) {
    Stage stage("merge");
    code = jobs::run_pan_merge(world, merge_results, merge_out, jobs::command_line(argc, argv));
  }

  if (checksum->parsed()) {
    std::string text;
    mpi::agree(world, [&] {
      auto file = io::File::open(checksum_path);
      text = io::hash_hex(io::content_hash(file, {{"/provenance/run"}, {}})) + "  " + checksum_path + "\n";
    });
    if (session.is_root()) std::fputs(text.c_str(), stdout);
  }

  if (info->parsed() || probe->parsed()) {
    // Serial work: every rank checks (so all agree on errors), rank 0 prints.
    std::string text;
    mpi::agree(world, [&] { text = info->parsed() ? jobs::bank_info(bank_path) : jobs::probe_csv(probe_req); });
    if (session.is_root()) std::fputs(text.c_str(), stdout);
  }

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
