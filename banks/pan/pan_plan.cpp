#include "banks/pan/pan_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "banks/pan/pan_job.hpp"
#include "cli/run_options.hpp"

namespace clatter::jobs {
namespace {

struct Calibration {
  double rate = 0;            // cell-updates/s per rank, wall time of a whole solve (setup included)
  double bytes_per_cell = 0;
  double surface_s = 0;       // rank 0's seconds per term of a series-sample heard through the Kirchhoff
                              // surface (kirchhoff_terms: faces x mirror images)
  std::string how;
};

// A small solve with the sweep's own physics, cell size and Kirchhoff surface: the body's bounding
// sphere plus a few cells, so the per-cell costs (bulk, cut cells, layer) resemble a task's. Solved
// twice, with and without its listeners through the surface, for the cost of each (a task hears
// directions x (radii + 1) series, a cost that grows with the record, not the grid).
Calibration calibrate(const PanParams& params, double given_rate) {
  PanParams small = params;
  const double dx = small.grid_dx_m, a = small.proxies_a_m;
  // The sphere proxy: the whole ball for a surface, so hearing is well above the timer's noise;
  // tasks scale it by their own surfaces (kirchhoff_terms). A mesh entry's cells step at the
  // same rate, the full domain's too.
  small.objects_meshes.clear();
  small.objects_scene.clear();
  small.scene_meshes.clear();
  small.proxies_list_m = {{a, a}};
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
  // Heard first: the first solve of a process also pays for its first touch of the memory.
  const double heard_wall = timed([&] { build_proxy(MPI_COMM_SELF, spec, 0, {}, 0); });
  const double wall = timed([&] { r = run_solve(MPI_COMM_SELF, spec.solve, 0); });
  const double series = pan_series_per_task(spec);
  Calibration c;
  const double updates = static_cast<double>(r.cells) * (spec.solve.n_samples - 1);
  c.bytes_per_cell = r.bytes / static_cast<double>(r.cells);
  c.rate = given_rate > 0 ? given_rate : updates / wall;
  const double terms = kirchhoff_terms(spec, spec.bodies[0]);
  c.surface_s = std::max(0.0, heard_wall - wall) / (series * spec.solve.n_samples * terms);
  c.how = given_rate > 0 ? "given with --rate"
                         : fmt::format("measured here: {:.3g} M cells x {} steps in {:.2f} s on 1 rank, setup included",
                                       static_cast<double>(r.cells) / 1e6, spec.solve.n_samples - 1, wall);
  c.how += fmt::format("; {:.3g} ns per face-image and sample of a series through the Kirchhoff surface ({:.0f} series "
                       "x {:.0f} face-images in {:.2f} s)",
                       c.surface_s * 1e9, series, terms, heard_wall - wall);
  return c;
}

// The cost of one task: an entry of one octant solves spec.solve's octant grid, one of eight
// octants (a mesh without mirror symmetry) spec.solve_full's whole domain and hears every octant.
// Ranks of a group split the cells; the surface's series are rank 0's alone, each costing the
// body's surface terms (kirchhoff_terms: a needle's box-cut surface has a fraction of the ball's).
struct TaskCost {
  double cells = 0;
  double updates = 0;  // cell-updates
  double series = 0;   // series heard through the surface (directions x (radii + 1), every octant)
  double terms = 0;    // per series and sample: the surface's faces x mirror images
  double task_s = 0;
  double rank_bytes = 0, listener_bytes = 0;  // rank_bytes: per rank, the listener records counted
};

// The cost model: tasks handed out in order to the groups (list_schedule_s).
struct PlanCost {
  int steps = 0;
  Calibration cal;
  std::vector<TaskCost> body;  // per entry
  std::vector<double> task_s;
  int groups = 0;
  double wall_s = 0, limit_s = 0;
  int cores = 0, nodes = 0;  // cores per node, nodes of the job
};

TaskCost task_cost(const PanSpec& spec, const PanBody& body, const Calibration& cal, int ranks_per_task) {
  const int octants = body.shape.octants;
  const SolveSpec& solve = octants == 8 ? spec.solve_full : spec.solve;
  TaskCost t;
  const auto& g = solve.problem.grid;
  t.cells = static_cast<double>(g.n[0]) * g.n[1] * g.n[2];
  // With refinement a task solves field 3 too, its floor's yardstick (build_proxy): a bound.
  t.updates = t.cells * (solve.n_samples - 1) * (spec.direction_tolerance > 0 ? 2 : 1);
  t.series = pan_series_per_task(spec) * body.heard_octants();
  t.terms = kirchhoff_terms(spec, body);
  t.task_s = t.updates / (cal.rate * ranks_per_task) + t.series * solve.n_samples * t.terms * cal.surface_s;
  t.listener_bytes = (static_cast<double>(solve.listeners_m.size()) * 4 + t.series * 8) * solve.n_samples;
  t.rank_bytes = cal.bytes_per_cell * t.cells / ranks_per_task + t.listener_bytes;
  return t;
}

PlanCost plan_cost(const PanParams& params, const PanSpec& spec, const std::vector<PanTask>& tasks, const PlanOptions& o) {
  PlanCost c;
  c.steps = spec.solve.n_samples - 1;
  c.cal = calibrate(params, o.rate);
  for (const auto& b : spec.bodies) c.body.push_back(task_cost(spec, b, c.cal, o.ranks_per_task));
  for (const auto& t : tasks) c.task_s.push_back(c.body[t.proxy].task_s);
  c.groups = o.ranks / o.ranks_per_task;
  c.wall_s = list_schedule_s(c.task_s, c.groups);
  c.limit_s = 1.5 * c.wall_s + 600;  // margin for slower nodes and queue start-up, plus the 120 s signal
  c.cores = o.cores_per_node > 0 ? o.cores_per_node : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  c.nodes = (o.ranks + c.cores - 1) / c.cores;
  return c;
}

std::string task_line(const char* what, const SolveSpec& solve, const TaskCost& t, const PanSpec& spec, int steps) {
  const auto& g = solve.problem.grid;
  return fmt::format("  per task{}: {} grid {}x{}x{} = {:.3g} M cells, {} steps: {:.3g} cell-updates; {}{:.0f} series "
                     "through the Kirchhoff surface{}\n",
                     what, g.octant ? "octant" : "full", g.n[0], g.n[1], g.n[2], t.cells / 1e6, steps, t.updates,
                     spec.direction_tolerance > 0 ? "up to " : "", t.series,
                     spec.direction_tolerance > 0 ? fmt::format(" (adaptive directions: fit.max_directions = {} bounds "
                                                                "them; the time is a bound too)", spec.max_directions)
                                                  : std::string());
}

// The plan as printed: the sweep, the cost per task and of the job, and every task.
std::string pan_report(const PanSpec& spec, const std::vector<PanTask>& tasks, const PlanOptions& o, const PlanCost& c) {
  const bool meshes = !spec.bodies.empty() && spec.bodies[0].mesh;
  std::string out = fmt::format("plan: {}: {} {} x {} fields = {} tasks\n", o.config_path.empty() ? "defaults" : o.config_path,
                                spec.bodies.size(), meshes ? "meshes" : "proxies", spec.solve.fields.size(), tasks.size());
  // One line per grid the entries use: the octant's, and the full domain's for eight octants.
  const TaskCost* largest = nullptr;
  for (int octants : {1, 8})
    for (std::size_t b = 0; b < spec.bodies.size(); ++b)
      if (spec.bodies[b].shape.octants == octants) {
        const bool both = std::any_of(spec.bodies.begin(), spec.bodies.end(), [&](const PanBody& x) { return x.shape.octants != octants; });
        out += task_line(!both ? "   " : octants == 1 ? " (1 octant)  " : " (8 octants) ", octants == 8 ? spec.solve_full : spec.solve,
                         c.body[b], spec, c.steps);
        if (!largest || c.body[b].rank_bytes > largest->rank_bytes) largest = &c.body[b];
        break;
      }
  if (largest)
    out += fmt::format("  memory:      {:.1f} bytes/cell -> {:.0f} MiB per rank with {} rank(s) per task (+ {:.0f} MiB of "
                       "listener records on each group's rank 0, counted), the largest task's\n",
                       c.cal.bytes_per_cell, largest->rank_bytes / 1048576.0, o.ranks_per_task, largest->listener_bytes / 1048576.0);
  out += fmt::format("  calibration: {:.3g} cell-updates/s per rank ({})\n", c.cal.rate, c.cal.how);
  out += fmt::format("  job:         {} ranks on {} node(s) of {} cores, {} group(s) of {}, each taking the next task "
                     "when free\n",
                     o.ranks, c.nodes, c.cores, c.groups, o.ranks_per_task);
  out += fmt::format("  predicted:   {} wall; time limit with 1.5x margin + 10 min: {}\n", clock_text(c.wall_s),
                     clock_text(c.limit_s));
  out += "  tasks (each hears its series through a surface of faces x mirror images; the box-cut surface of a flat\n"
         "  or long body has fewer):\n";
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const auto& t = tasks[i];
    const PanBody& b = spec.bodies[t.proxy];
    out += fmt::format("    {}  {}  field {}  {:.0f} face-images  {}{}\n", t.name, b.label(), t.field, c.body[t.proxy].terms,
                       clock_text(c.task_s[i]),
                       b.shape.octants == 1        ? ""
                       : b.heard_octants() == 8    ? "  (8 octants)"
                                                   : fmt::format("  (8 octants, {} heard: mirror planes)", b.heard_octants()));
  }
  return out;
}

}  // namespace

PlanEstimate pan_plan_estimate(const PanParams& params, const PlanOptions& o) {
  const PanSpec spec = make_pan_spec(params);
  const auto tasks = pan_tasks(spec);
  const PlanCost cost = plan_cost(params, spec, tasks, o);
  return {pan_report(spec, tasks, o, cost), cost.task_s, cost.nodes};
}

}  // namespace clatter::jobs
