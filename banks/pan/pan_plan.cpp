#include "banks/pan/pan_plan.hpp"

#include <fmt/format.h>

#include <chrono>
#include <thread>

#include "banks/pan/pan_job.hpp"
#include "cli/run_options.hpp"

namespace clatter::jobs {
namespace {

struct Calibration {
  double rate = 0;            // cell-updates/s per rank, wall time of a whole solve (setup included)
  double bytes_per_cell = 0;
  double surface_s = 0;       // rank 0's seconds per series-sample heard through the Kirchhoff surface
  std::string how;
};

// A small solve with the sweep's own physics, cell size and Kirchhoff surface: the body's bounding
// sphere plus a few cells, so the per-cell costs (bulk, cut cells, layer) resemble a task's. Solved
// twice, with and without its listeners through the surface, for the cost of each (a task hears
// directions x (radii + 1) series, a cost that grows with the record, not the grid).
Calibration calibrate(const io::Config& config, double given_rate) {
  PanParams small = parse_pan_params(config);
  const double dx = small.grid_dx_m, a = small.proxies_a_m;
  small.fit_radii_m = {a + 6 * dx, a + 7 * dx};
  small.time_tail_s = 64 * small.time_dt_s;
  small.solve_fields = {1};
  small.fit_direction_tolerance = 0;  // the layout's directions: a known series count
  const PanSpec spec = make_pan_spec(small);
  auto timed = [](auto&& work) {
    const auto t0 = std::chrono::steady_clock::now();
    work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  SolveResult r;
  const double wall = timed([&] { r = run_solve(MPI_COMM_SELF, spec.solve, 0); });
  const double heard_wall = timed([&] { build_proxy(MPI_COMM_SELF, spec, 0, {}, 0); });
  const double series = pan_series_per_task(spec);
  Calibration c;
  const double updates = static_cast<double>(r.cells) * (spec.solve.n_samples - 1);
  c.bytes_per_cell = r.bytes / static_cast<double>(r.cells);
  c.rate = given_rate > 0 ? given_rate : updates / wall;
  c.surface_s = std::max(0.0, heard_wall - wall) / (series * spec.solve.n_samples);
  c.how = given_rate > 0 ? "given with --rate"
                         : fmt::format("measured here: {:.3g} M cells x {} steps in {:.2f} s on 1 rank, setup included",
                                       static_cast<double>(r.cells) / 1e6, spec.solve.n_samples - 1, wall);
  c.how += fmt::format("; {:.3g} us per sample of a series through the Kirchhoff surface ({:.0f} series in {:.2f} s)",
                       c.surface_s * 1e6, series, heard_wall - wall);
  return c;
}

// The cost model. Tasks are equal in size: the sweep takes `waves` task times; ranks of a group
// split the cells.
struct PlanCost {
  double cells = 0;    // per task
  int steps = 0;
  double updates = 0;  // cell-updates per task
  double series = 0;   // series per task heard through the surface (directions x (radii + 1))
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
  // With refinement a task solves field 3 too, its floor's yardstick (build_proxy): a bound.
  c.updates = c.cells * c.steps * (spec.direction_tolerance > 0 ? 2 : 1);
  c.cal = calibrate(config, o.rate);
  c.groups = o.ranks / o.ranks_per_task;
  c.waves = (n_tasks + static_cast<std::size_t>(c.groups) - 1) / static_cast<std::size_t>(c.groups);
  c.series = pan_series_per_task(spec);
  // The grid's steps split over the group's ranks; the surface's series are rank 0's alone.
  c.task_s = c.updates / (c.cal.rate * o.ranks_per_task) + c.series * spec.solve.n_samples * c.cal.surface_s;
  c.wall_s = static_cast<double>(c.waves) * c.task_s;
  c.limit_s = 1.5 * c.wall_s + 600;  // margin for slower nodes and queue start-up, plus the 120 s signal
  c.listener_bytes = (static_cast<double>(spec.solve.listeners_m.size()) * 4 + c.series * 8) * spec.solve.n_samples;
  c.rank_bytes = c.cal.bytes_per_cell * c.cells / o.ranks_per_task + c.listener_bytes;
  c.cores = o.cores_per_node > 0 ? o.cores_per_node : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  c.nodes = (o.ranks + c.cores - 1) / c.cores;
  return c;
}

// The plan as printed: the sweep, the cost per task and of the job, and every task.
std::string pan_report(const PanSpec& spec, const std::vector<PanTask>& tasks, const PlanOptions& o, const PlanCost& c) {
  const auto& g = spec.solve.problem.grid;
  std::string out = fmt::format("plan: {}: {} {} x {} fields = {} tasks\n", o.config_path.empty() ? "defaults" : o.config_path,
                                spec.bodies.size(), !spec.bodies.empty() && spec.bodies[0].mesh ? "meshes" : "proxies",
                                spec.solve.fields.size(), tasks.size());
  out += fmt::format("  per task:    {} grid {}x{}x{} = {:.3g} M cells, {} steps: {:.3g} cell-updates; {}{:.0f} series "
                     "through the Kirchhoff surface{}\n",
                     g.octant ? "octant" : "full", g.n[0], g.n[1], g.n[2], c.cells / 1e6, c.steps, c.updates,
                     spec.direction_tolerance > 0 ? "up to " : "", c.series,
                     spec.direction_tolerance > 0 ? fmt::format(" (adaptive directions: fit.max_directions = {} bounds "
                                                                "them; the time is a bound too)", spec.max_directions)
                                                  : std::string());
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
    out += fmt::format("    {}  {}  field {}  {:.3g} cell-updates\n", t.name, spec.bodies[t.proxy].label(), t.field,
                       c.updates);
  return out;
}

}  // namespace

PlanEstimate pan_plan_estimate(const io::Config& config, const PlanOptions& o) {
  const PanSpec spec = make_pan_spec(config);
  const auto tasks = pan_tasks(spec);
  const PlanCost cost = plan_cost(config, spec, tasks.size(), o);
  return {pan_report(spec, tasks, o, cost), std::vector<double>(tasks.size(), cost.task_s), cost.nodes};
}

}  // namespace clatter::jobs
