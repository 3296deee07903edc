#include "banks/plan.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <thread>

#include "banks/commands.hpp"
#include "banks/registry.hpp"
#include "core/errors.hpp"
#include "io/text_file.hpp"
#include "mpi/comm.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

std::string sweep_command(const PlanOptions& o, const std::string& results, const std::string& extra) {
  return fmt::format("{} {} --config {} --out {} --results {} --ranks-per-task {} --resume --progress-interval 60 "
                     "--log-view{}",
                     o.binary, o.kind, o.config_path, o.out, results, o.ranks_per_task, extra);
}

// Slurm signals the ranks themselves a lead before the limit (--signal=TERM@LEAD: 120 s, or for a
// modal plan its longest task; no B: a signal to srun would make it end the step with SIGKILL
// after KillWait); they stop cleanly and exit 3. The
// job then requeues itself, and --resume makes every start skip the verified finished tasks.
std::string run_block(const std::string& command) {
  return fmt::format(R"(export OMP_NUM_THREADS=1
rc=0
srun --mpi=pmix {} || rc=$?
)", command);
}

void write_script(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw InputError(fmt::format("--sbatch {}: cannot write the file", path));
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

// The job reads exactly the planned config (file and --set overrides), frozen next to the script;
// returns the options of the job, reading that copy.
PlanOptions freeze_config(const io::Config& config, const PlanOptions& o) {
  PlanOptions job = o;
  job.config_path = fs::absolute(o.sbatch + ".toml").string();
  std::ofstream toml(job.config_path);
  toml << config.to_toml();
  if (!toml) throw InputError(fmt::format("--sbatch {}: cannot write {}", o.sbatch, job.config_path));
  return job;
}

void write_merge_script(const PlanOptions& o, const std::string& results) {
  write_script(o.sbatch + ".merge", fmt::format(R"(#!/bin/bash
# Merges the slices of {} into {} once every array element succeeded (--dependency=afterok).
#SBATCH --job-name=clatter-{}-merge
#SBATCH --ntasks=1
#SBATCH --time=0:30:00
#SBATCH --output=clatter-{}-merge-%j.out
set -u
srun --mpi=pmix {} merge --results {} --out {}
)", o.sbatch, o.out, o.kind, o.kind, o.binary, results, o.out));
}

// Writes the sweep script (and with --array the merge script) and returns the report's lines on them.
std::string write_sbatch_scripts(const io::Config& config, const PlanOptions& o, const PlanEstimate& e) {
  const std::string results = o.results.empty() ? o.out + ".tasks" : o.results;
  const PlanOptions job = freeze_config(config, o);
  const std::size_t n_tasks = e.task_s.size();
  const int groups = o.ranks / o.ranks_per_task;
  const std::string header = fmt::format(
      "#!/bin/bash\n# Written by clatter-bank plan for {} ({} tasks; predicted {} on {} ranks).\n", job.config_path,
      n_tasks, clock_text(list_schedule_s(e.task_s, groups)), o.ranks);
  // One sweep job: the whole bank, or (array) one slice of it per element. Either way it requeues
  // itself when interrupted (exit 3) and every start resumes.
  const bool array = o.array > 0;
  const std::size_t per_element =
      array ? (n_tasks + static_cast<std::size_t>(o.array) - 1) / static_cast<std::size_t>(o.array) : n_tasks;
  double slowest_element_s = 0;  // element K runs tasks t with t % array == K
  for (int k = 0; k < std::max(o.array, 1); ++k) {
    std::vector<double> mine;
    for (std::size_t t = static_cast<std::size_t>(k); t < n_tasks; t += static_cast<std::size_t>(std::max(o.array, 1)))
      mine.push_back(e.task_s[t]);
    slowest_element_s = std::max(slowest_element_s, list_schedule_s(mine, groups));
  }
  const double job_limit_s = 1.5 * slowest_element_s + 600 + e.signal_lead_s;
  write_script(o.sbatch,
               header + fmt::format(R"(#SBATCH --job-name=clatter-{}{}
{}#SBATCH --nodes={}
#SBATCH --ntasks={}
#SBATCH --time={}
#SBATCH --signal=TERM@{}
#SBATCH --requeue
#SBATCH --open-mode=append
#SBATCH --output=clatter-{}-{}.out
set -u
{}if [ "$rc" -eq 3 ]; then echo "clatter: interrupted (exit 3), requeueing"; scontrol requeue "{}"; fi
exit "$rc"
)",
                                    o.kind, array ? "-array" : "",
                                    array ? fmt::format("#SBATCH --array=0-{}\n", o.array - 1) : "", e.nodes, o.ranks,
                                    clock_text(job_limit_s), e.signal_lead_s, o.kind, array ? "%A_%a" : "%j",
                                    run_block(sweep_command(
                                        job, results, array ? " --slice ${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}" : "")),
                                    array ? "${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}" : "$SLURM_JOB_ID"));
  if (!array) return fmt::format("  wrote {}: submit with `sbatch {}`\n", o.sbatch, o.sbatch);
  write_merge_script(o, results);
  return fmt::format("  wrote {} ({} elements of ~{} tasks, limit {}) and {}.merge; submit with\n"
                     "    jid=$(sbatch --parsable {}) && sbatch --dependency=afterok:${{jid%%;*}} {}.merge\n",
                     o.sbatch, o.array, per_element, clock_text(job_limit_s), o.sbatch, o.sbatch, o.sbatch);
}

}  // namespace

double list_schedule_s(const std::vector<double>& task_s, int groups) {
  std::vector<double> free_at(static_cast<std::size_t>(std::max(groups, 1)), 0.0);
  for (double t : task_s) *std::min_element(free_at.begin(), free_at.end()) += t;
  return *std::max_element(free_at.begin(), free_at.end());
}

namespace {

// The kind of a plan: --kind, or the one kind whose schema accepts the config file and the --set
// keys (each kind's keys are its own); with neither, the first kind registered (pan), so
// `plan --ranks 64` sizes the paper's PAN bank.
const BankKind& plan_kind(const RunContext& context, const std::string& kind, const ConfigOptions& options) {
  if (!kind.empty()) return kind_named(kind, "--kind");
  if (options.config_path.empty() && options.sets.empty()) return *bank_kinds().front();
  std::string text;
  mpi::agree(context.world, [&] {
    if (context.is_root && !options.config_path.empty()) text = io::read_text_file(options.config_path);
  });
  text = mpi::broadcast(context.world, text);
  std::vector<const BankKind*> fits;
  for (const BankKind* k : bank_kinds()) {
    try {
      io::Config config(k->schema());
      config.merge_toml(text, options.config_path);
      for (const auto& s : options.sets) config.set(s);
      fits.push_back(k);
    } catch (const InputError&) {
    }
  }
  if (fits.size() == 1) return *fits.front();
  std::string names;
  for (const BankKind* k : bank_kinds()) names += (names.empty() ? "" : ", ") + std::string(k->name());
  throw InputError(fmt::format("plan: {} of the bank kinds' schemas accept{} this config; name its kind with --kind "
                               "({})",
                               fits.empty() ? "none" : "several", fits.empty() ? "s" : "", names));
}

std::string run_plan(const BankKind& kind, const io::Config& config, const PlanOptions& o) {
  if (o.ranks < 1) throw InputError(fmt::format("--ranks {}: must be >= 1", o.ranks));
  if (o.ranks_per_task < 1 || o.ranks % o.ranks_per_task != 0)
    throw InputError(fmt::format("--ranks {} --ranks-per-task {}: the ranks per task must divide the ranks", o.ranks,
                                 o.ranks_per_task));
  const PlanEstimate e = kind.plan(config, o);
  std::string out = e.report;
  if (!o.sbatch.empty()) out += write_sbatch_scripts(config, o, e);
  return out;
}

}  // namespace

Command add_plan_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("plan", "predict a sweep's cost (per task work, memory per rank, wall time from a "
                                            "calibration run here) and write Slurm batch scripts");
  auto options = std::make_shared<ConfigOptions>();
  auto plan = std::make_shared<PlanOptions>();
  auto kind = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  add_config_options(*app, *options);
  add_out_option(*app, *out, "the bank the job will write (default: the kind's, e.g. bank.h5)");
  app->add_option("--kind", *kind, "the bank kind (default: the one whose schema accepts the config)");
  app->add_option("--ranks", plan->ranks, "MPI ranks of the job")->capture_default_str();
  app->add_option("--ranks-per-task", plan->ranks_per_task, "ranks per task")->capture_default_str();
  app->add_option("--cores-per-node", plan->cores_per_node, "cores per node (default: this machine's)");
  app->add_option("--rate", plan->rate, "cell-updates/s per rank instead of measuring (e.g. from a stage table)");
  app->add_option("--results", plan->results, "results folder of the job (default: OUT.tasks)");
  app->add_option("--sbatch", plan->sbatch, "write a ready sbatch script here");
  app->add_option("--array", plan->array, "with --sbatch: a job array of N elements and a merge job (FILE.merge)");
  return {app, [options, plan, kind, out](const RunContext& context) -> int {
            const BankKind* bank = nullptr;
            mpi::agree(context.world, [&] { bank = &plan_kind(context, *kind, *options); });
            plan->kind = bank->name();
            if (out->empty()) *out = bank->default_out();
            const auto config = job_config(context.world, bank->schema(), *options, bank->builtin_config());
            if (!config) return kExitOk;
            // The scripts run elsewhere and later: every path in them is absolute.
            plan->config_path = options->config_path.empty() ? "" : fs::absolute(options->config_path).string();
            plan->out = fs::absolute(*out).string();
            if (!plan->results.empty()) plan->results = fs::absolute(plan->results).string();
            plan->binary = fs::canonical("/proc/self/exe").string();
            const auto libraries = bank->start_libraries(context);
            std::string report;
            mpi::agree(context.world, [&] {
              if (context.is_root) report = run_plan(*bank, *config, *plan);
            });
            if (context.is_root) std::fputs(report.c_str(), stdout);
            return kExitOk;
          }};
}

}  // namespace clatter::jobs
