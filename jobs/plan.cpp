#include "jobs/plan.hpp"

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

#include "core/errors.hpp"
#include "jobs/command.hpp"
#include "jobs/modal_plan.hpp"
#include "jobs/modal_spec.hpp"
#include "jobs/pan_job.hpp"
#include "jobs/run_options.hpp"
#include "io/text_file.hpp"
#include "mpi/comm.hpp"
#include "petsc/session.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

struct Calibration {
  double rate = 0;            // cell-updates/s per rank, wall time of a whole solve (setup included)
  double bytes_per_cell = 0;
  std::string how;
};

// A small solve with the sweep's own physics and cell size: the body's bounding sphere plus a few
// cells, so the per-cell costs (bulk, cut cells, layer) resemble a task's.
Calibration calibrate(const io::Config& config, double given_rate) {
  PanParams small = parse_pan_params(config);
  const double dx = small.grid_dx_m, a = small.proxies_a_m;
  small.fit_radii_m = {a + 2.5 * dx, a + 3 * dx};
  small.fit_terms = 1;
  small.time_tail_s = 64 * small.time_dt_s;
  small.solve_fields = {1};
  const PanSpec spec = make_pan_spec(small);
  Calibration c;
  const auto t0 = std::chrono::steady_clock::now();
  const SolveResult r = run_solve(MPI_COMM_SELF, spec.solve, 0);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double updates = static_cast<double>(r.cells) * (spec.solve.n_samples - 1);
  c.bytes_per_cell = r.bytes / static_cast<double>(r.cells);
  c.rate = given_rate > 0 ? given_rate : updates / wall;
  c.how = given_rate > 0 ? "given with --rate"
                         : fmt::format("measured here: {:.3g} M cells x {} steps in {:.2f} s on 1 rank, setup included",
                                       static_cast<double>(r.cells) / 1e6, spec.solve.n_samples - 1, wall);
  return c;
}

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

// The cost model. Tasks are equal in size: the sweep takes `waves` task times; ranks of a group
// split the cells.
struct PlanCost {
  double cells = 0;    // per task
  int steps = 0;
  double updates = 0;  // cell-updates per task
  Calibration cal;
  int groups = 0;
  std::size_t waves = 0;
  double task_s = 0, wall_s = 0, limit_s = 0;
  double listener_bytes = 0, rank_bytes = 0;  // rank_bytes: per rank, the listener records counted
  int cores = 0, nodes = 0;                    // cores per node, nodes of the job
};

PlanCost plan_cost(const io::Config& config, const PanSpec& spec, std::size_t n_tasks, const PlanOptions& o) {
  PlanCost c;
  const auto& g = spec.solve.problem.grid;
  c.cells = static_cast<double>(g.n[0]) * g.n[1] * g.n[2];
  c.steps = spec.solve.n_samples - 1;
  c.updates = c.cells * c.steps;
  c.cal = calibrate(config, o.rate);
  c.groups = o.ranks / o.ranks_per_task;
  c.waves = (n_tasks + static_cast<std::size_t>(c.groups) - 1) / static_cast<std::size_t>(c.groups);
  c.task_s = c.updates / (c.cal.rate * o.ranks_per_task);
  c.wall_s = static_cast<double>(c.waves) * c.task_s;
  c.limit_s = 1.5 * c.wall_s + 600;  // margin for slower nodes and queue start-up, plus the 120 s signal
  c.listener_bytes = static_cast<double>(spec.solve.listeners_m.size()) * 8 * spec.solve.n_samples * 4;
  c.rank_bytes = c.cal.bytes_per_cell * c.cells / o.ranks_per_task + c.listener_bytes;
  c.cores = o.cores_per_node > 0 ? o.cores_per_node : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  c.nodes = (o.ranks + c.cores - 1) / c.cores;
  return c;
}

// The plan as printed: the sweep, the cost per task and of the job, and every task.
std::string pan_report(const PanSpec& spec, const std::vector<PanTask>& tasks, const PlanOptions& o, const PlanCost& c) {
  const auto& g = spec.solve.problem.grid;
  std::string out = fmt::format("plan: {}: {} proxies x {} fields = {} tasks\n", o.config_path.empty() ? "defaults" : o.config_path,
                                spec.proxies_bc_m.size(), spec.solve.fields.size(), tasks.size());
  out += fmt::format("  per task:    {} grid {}x{}x{} = {:.3g} M cells, {} steps: {:.3g} cell-updates\n",
                     g.octant ? "octant" : "full", g.n[0], g.n[1], g.n[2], c.cells / 1e6, c.steps, c.updates);
  out += fmt::format("  memory:      {:.1f} bytes/cell -> {:.0f} MiB per rank with {} rank(s) per task (+ {:.0f} MiB of "
                     "listener records on each group's rank 0, counted)\n",
                     c.cal.bytes_per_cell, c.rank_bytes / 1048576.0, o.ranks_per_task, c.listener_bytes / 1048576.0);
  out += fmt::format("  calibration: {:.3g} cell-updates/s per rank ({})\n", c.cal.rate, c.cal.how);
  out += fmt::format("  job:         {} ranks on {} node(s) of {} cores, {} group(s) of {}; {} waves of {} per task\n",
                     o.ranks, c.nodes, c.cores, c.groups, o.ranks_per_task, c.waves, clock_text(c.task_s));
  out += fmt::format("  predicted:   {} wall; time limit with 1.5x margin + 10 min: {}\n", clock_text(c.wall_s),
                     clock_text(c.limit_s));
  out += "  tasks:\n";
  for (const auto& t : tasks)
    out += fmt::format("    {}  (B, C) = ({:.4g}, {:.4g}) m  field {}  {:.3g} cell-updates\n", t.name,
                       spec.proxies_bc_m[t.proxy][0], spec.proxies_bc_m[t.proxy][1], t.field, c.updates);
  return out;
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

PlanEstimate pan_estimate(const io::Config& config, const PlanOptions& o) {
  const PanSpec spec = make_pan_spec(config);
  const auto tasks = pan_tasks(spec);
  const PlanCost cost = plan_cost(config, spec, tasks.size(), o);
  return {pan_report(spec, tasks, o, cost), std::vector<double>(tasks.size(), cost.task_s), cost.nodes};
}

}  // namespace

double list_schedule_s(const std::vector<double>& task_s, int groups) {
  std::vector<double> free_at(static_cast<std::size_t>(std::max(groups, 1)), 0.0);
  for (double t : task_s) *std::min_element(free_at.begin(), free_at.end()) += t;
  return *std::max_element(free_at.begin(), free_at.end());
}

std::string run_plan(const io::Config& config, const PlanOptions& o) {
  if (o.ranks < 1) throw InputError(fmt::format("--ranks {}: must be >= 1", o.ranks));
  if (o.ranks_per_task < 1 || o.ranks % o.ranks_per_task != 0)
    throw InputError(fmt::format("--ranks {} --ranks-per-task {}: the ranks per task must divide the ranks", o.ranks,
                                 o.ranks_per_task));
  const PlanEstimate e = o.kind == "modal" ? modal_plan_estimate(config, o) : pan_estimate(config, o);
  std::string out = e.report;
  if (!o.sbatch.empty()) out += write_sbatch_scripts(config, o, e);
  return out;
}

Command add_plan_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("plan", "predict a PAN or modal sweep's cost (per task work, memory per rank, wall "
                                            "time from a calibration solve run here) and write Slurm batch scripts");
  auto options = std::make_shared<JobOptions>();
  auto plan = std::make_shared<PlanOptions>();
  options->out = "bank.h5";
  add_job_options(*app, *options, "the bank the job will write", false);
  app->add_option("--ranks", plan->ranks, "MPI ranks of the job")->capture_default_str();
  app->add_option("--ranks-per-task", plan->ranks_per_task, "ranks per task")->capture_default_str();
  app->add_option("--cores-per-node", plan->cores_per_node, "cores per node (default: this machine's)");
  app->add_option("--rate", plan->rate, "cell-updates/s per rank instead of measuring (e.g. from a stage table)");
  app->add_option("--results", plan->results, "results folder of the job (default: OUT.tasks)");
  app->add_option("--sbatch", plan->sbatch, "write a ready sbatch script here");
  app->add_option("--array", plan->array, "with --sbatch: a job array of N elements and a merge job (FILE.merge)");
  return {app, [options, plan](const JobContext& context) -> int {
            // The bank kind is the config file's: a modal config has a [modes] table.
            std::string text;
            mpi::agree(context.world, [&] {
              if (!options->config_path.empty()) text = io::read_text_file(options->config_path);
            });
            plan->kind = is_modal_config(text) ? "modal" : "pan";
            if (plan->kind == "modal" && options->out == "bank.h5") options->out = "modal.h5";
            const auto config = job_config(context.world, plan->kind == "modal" ? modal_schema() : pan_schema(), *options);
            if (!config) return kExitOk;
            // The scripts run elsewhere and later: every path in them is absolute.
            plan->config_path = options->config_path.empty() ? "" : fs::absolute(options->config_path).string();
            plan->out = fs::absolute(options->out).string();
            if (!plan->results.empty()) plan->results = fs::absolute(plan->results).string();
            plan->binary = fs::canonical("/proc/self/exe").string();
            std::optional<petsc::Session> petsc;
            if (plan->kind == "modal") petsc.emplace(context.world);
            std::string report;
            mpi::agree(context.world, [&] {
              if (context.is_root) report = run_plan(*config, *plan);
            });
            if (context.is_root) std::fputs(report.c_str(), stdout);
            return kExitOk;
          }};
}

}  // namespace clatter::jobs
