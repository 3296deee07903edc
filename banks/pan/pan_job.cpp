#include "banks/pan/pan_job.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "kernels/fdtd/listeners.hpp"
#include "kernels/pan/directions.hpp"
#include "kernels/pan/fit.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {

namespace pan = kernels::pan;

TaskWriter run_pan_task(MPI_Comm group, const PanSpec& spec, const PanTask& task, double progress_interval_s) {
  PanSpec one = spec;
  one.solve.fields = {task.field};
  auto result = build_proxy(group, one, task.proxy, {}, progress_interval_s);
  if (mpi::rank(group) != 0) return {};
  model::PanTaskResult r;
  r.proxy = static_cast<std::uint32_t>(task.proxy);
  r.b_m = result.proxy.b_m;
  r.c_m = result.proxy.c_m;
  r.field = task.field;
  r.directions = std::move(result.proxy.fields[static_cast<std::size_t>(task.field - 1)]);
  return [r = std::move(r), values = spec.radii_m.size() + 1](io::File& file, const std::string& group_name) {
    io::write_pan_task(file, group_name, r, values);
  };
}

model::PanBank merge_pan_results(const PanSpec& spec, const std::string& results_dir, const std::string& config_toml) {
  model::PanBank bank;
  bank.header = pan_header(spec);
  for (std::size_t p = 0; p < spec.proxies_bc_m.size(); ++p) {
    model::PanProxy proxy;
    proxy.b_m = spec.proxies_bc_m[p][0];
    proxy.c_m = spec.proxies_bc_m[p][1];
    bank.proxies.push_back(std::move(proxy));
  }
  const auto tasks = pan_tasks(spec);
  bank.sweep.sweep_id = io::sweep_id(config_toml);
  bank.sweep.tasks_total = static_cast<std::uint32_t>(tasks.size());
  for (const auto& t : tasks) {
    const std::string label = fmt::format("{} (B, C) = ({:.4g}, {:.4g}) m, field {}", t.name, spec.proxies_bc_m[t.proxy][0],
                                          spec.proxies_bc_m[t.proxy][1], t.field);
    if (!task_done(results_dir, t.name, label, config_toml, bank.sweep)) continue;
    auto file = io::File::open(io::task_path(results_dir, t.name));
    auto r = io::read_pan_task(file, "/result", bank.header.values(), bank.header.directions.size(), spec.length);
    if (r.proxy != t.proxy || r.field != t.field)
      throw InputError(fmt::format("{}: holds proxy {} field {}, expected {} field {}", file.path(), r.proxy, r.field,
                                   t.proxy, t.field));
    bank.proxies[t.proxy].fields[static_cast<std::size_t>(t.field - 1)] = std::move(r.directions);
  }
  return bank;
}

namespace {

// The far field on the fit's frame: coefficient sample n is at the retarded time
// tau = t_first + (n - lead - delay) dt, t_first the solve's first sample (fit.hpp, pan_spec.hpp).
std::vector<double> frame_far_field(const PanSpec& spec, const kernels::fdtd::KirchhoffSeries& far, int delay_steps) {
  const double dt = spec.solve.problem.dt_s, t_first = -spec.solve.i_time_zero * dt;
  const long offset = std::lround((t_first - far.t_first_s) / dt) - spec.lead_steps - delay_steps;
  std::vector<double> out(spec.length, 0.0);
  for (std::size_t n = 0; n < out.size(); ++n) {
    const long k = static_cast<long>(n) + offset;
    if (k >= 0 && k < far.valid_end) out[n] = far.value[static_cast<std::size_t>(k)];
  }
  return out;
}

// How a stored direction is aligned (kernels/pan/fit.hpp support_delay_samples): its whole steps
// go to the fit, its fraction to the surface's delay sums as an advance.
struct Alignment {
  int whole_steps = 0;
  double advance_s = 0;
};
Alignment alignment(const PanSpec& spec, std::size_t proxy, const std::array<double, 3>& d) {
  const double dt = spec.solve.problem.dt_s;
  const double delay = pan::support_delay_samples(d, spec.a_m, spec.proxies_bc_m[proxy][0], spec.proxies_bc_m[proxy][1],
                                                  spec.solve.problem.c_m_s, dt);
  const int whole = static_cast<int>(std::floor(delay));
  return {whole, -(delay - whole) * dt};
}

}  // namespace

ProxyResult build_proxy(MPI_Comm comm, const PanSpec& spec, std::size_t proxy,
                        const std::vector<std::array<double, 3>>& extra_listeners_m, double progress_interval_s) {
  namespace fdtd = kernels::fdtd;
  SolveSpec s = spec.solve;
  const double b_m = spec.proxies_bc_m[proxy][0], c_m = spec.proxies_bc_m[proxy][1];
  s.problem.body = {spec.a_m, b_m, c_m};
  // make_pan_spec checked the radii; the extra listeners are new, heard through the Kirchhoff
  // surface like them, anywhere outside it.
  for (std::size_t l = 0; l < extra_listeners_m.size(); ++l)
    if (auto why = surface_listener_problem(s, extra_listeners_m[l]))
      throw InputError(fmt::format("extra listener {} for proxy (B, C) = ({}, {}): {}", l + 1, b_m, c_m, *why));
  ProxyResult out;
  out.proxy.b_m = b_m;
  out.proxy.c_m = c_m;
  const auto directions = pan::direction_vertices(spec.divisions);
  std::vector<int> shifts;
  for (int k : spec.shift_steps) shifts.push_back(k - spec.lead_steps);
  const pan::Fitter fitter(spec.radii_m, shifts, spec.length);
  const std::size_t ns = static_cast<std::size_t>(s.n_samples), m = spec.radii_m.size();
  // Rank 0, per field, while its surface is alive: every direction heard at its radii and at
  // infinity, aligned by its support distance (the whole steps in the fit, the fraction here).
  auto hear = [&](std::size_t fi, const fdtd::SurfaceField& surface) {
    auto& dirs = out.proxy.fields[static_cast<std::size_t>(s.fields[fi] - 1)];
    std::vector<std::vector<float>> near(m, std::vector<float>(ns));
    std::vector<const float*> series;
    for (const auto& v : near) series.push_back(v.data());
    for (const auto& d : directions) {
      const Alignment a = alignment(spec, proxy, d);
      for (std::size_t i = 0; i < m; ++i) {
        const double r = spec.radii_m[i];
        const auto p = fdtd::pressure_at(surface, {r * d[0], r * d[1], r * d[2]}, a.advance_s);
        for (std::size_t k = 0; k < ns; ++k) near[i][k] = static_cast<float>(p.value[k]);
      }
      dirs.push_back(fitter.fit(series, ns, spec.epsilon, a.whole_steps, aligned_far_field(spec, proxy, surface, d)));
    }
    std::vector<float> extra(extra_listeners_m.size() * ns);
    for (std::size_t l = 0; l < extra_listeners_m.size(); ++l) {
      const auto p = fdtd::pressure_at(surface, extra_listeners_m[l]);
      for (std::size_t k = 0; k < ns; ++k) extra[l * ns + k] = static_cast<float>(p.value[k]);
    }
    out.extra_series.push_back(std::move(extra));
  };
  run_solve(comm, s, progress_interval_s, hear);
  if (mpi::rank(comm) != 0) return {};
  return out;
}

std::vector<double> aligned_far_field(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                      const std::array<double, 3>& d) {
  const Alignment a = alignment(spec, proxy, d);
  return frame_far_field(spec, kernels::fdtd::far_field(surface, d, a.advance_s), a.whole_steps);
}

double far_field_floor(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface) {
  double strongest = 0;
  for (const auto& d : pan::direction_vertices(spec.divisions)) {
    double e = 0;
    for (double x : aligned_far_field(spec, proxy, surface, d)) e += x * x;
    strongest = std::max(strongest, std::sqrt(e));
  }
  return 0.1 * strongest;
}

double far_field_miss(const std::vector<double>& interpolated, const std::vector<double>& truth, double floor) {
  double num = 0, den = 0;
  for (std::size_t n = 0; n < truth.size(); ++n) {
    num += (interpolated[n] - truth[n]) * (interpolated[n] - truth[n]);
    den += truth[n] * truth[n];
  }
  return std::sqrt(num / std::max(den, floor * floor));
}

DirectionRefinement refine_directions(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                      double tolerance, int max_levels, std::size_t max_vertices) {
  DirectionRefinement out{pan::DirectionMesh(spec.divisions, max_levels), 0, 0};
  auto& mesh = out.mesh;
  std::unordered_map<std::int64_t, std::vector<double>> far;  // by lattice point: vertices and split points
  auto at = [&](const pan::LatticePoint& p) -> const std::vector<double>& {
    auto it = far.find(p.key());
    if (it == far.end()) {
      it = far.emplace(p.key(), aligned_far_field(spec, proxy, surface, mesh.direction(p))).first;
      ++out.far_fields;
    }
    return it->second;
  };
  const double floor = far_field_floor(spec, proxy, surface);
  std::vector<double> sum(spec.length);
  auto miss = [&](const pan::LatticePoint& p, const pan::DirectionWeights& w) {
    pan::blend(w, [&](std::size_t v) -> const std::vector<double>& { return at(mesh.vertices()[v]); }, sum);
    return far_field_miss(sum, at(p), floor);
  };
  out.splits = pan::refine(mesh, miss, tolerance, max_vertices);
  return out;
}

}  // namespace clatter::jobs
