#include "banks/pan/pan_job.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

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
    proxy.delay_steps = proxy_delay_steps(spec, p);
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
std::vector<double> aligned_far_field(const PanSpec& spec, const kernels::fdtd::KirchhoffSeries& far, int delay_steps) {
  const double dt = spec.solve.problem.dt_s, t_first = -spec.solve.i_time_zero * dt;
  const long offset = std::lround((t_first - far.t_first_s) / dt) - spec.lead_steps - delay_steps;
  std::vector<double> out(spec.length, 0.0);
  for (std::size_t n = 0; n < out.size(); ++n) {
    const long k = static_cast<long>(n) + offset;
    if (k >= 0 && k < far.valid_end) out[n] = far.value[static_cast<std::size_t>(k)];
  }
  return out;
}

}  // namespace

ProxyResult build_proxy(MPI_Comm comm, const PanSpec& spec, std::size_t proxy,
                        const std::vector<std::array<double, 3>>& extra_listeners_m, double progress_interval_s) {
  SolveSpec s = spec.solve;
  s.problem.body = {spec.a_m, spec.proxies_bc_m[proxy][0], spec.proxies_bc_m[proxy][1]};
  // make_pan_spec checked the fitted listeners; the extra ones are new, heard through the
  // Kirchhoff surface like them, anywhere outside it.
  for (std::size_t l = 0; l < extra_listeners_m.size(); ++l) {
    const auto& x = extra_listeners_m[l];
    if (auto why = surface_listener_problem(s, x))
      throw InputError(fmt::format("extra listener {} for proxy (B, C) = ({}, {}): {}", l + 1,
                                   spec.proxies_bc_m[proxy][0], spec.proxies_bc_m[proxy][1], *why));
    s.surface_listeners_m.push_back(x);
  }
  SolveResult raw = run_solve(comm, s, progress_interval_s);
  ProxyResult out;
  if (mpi::rank(comm) != 0) return out;
  Stage stage("fit");
  out.proxy.b_m = spec.proxies_bc_m[proxy][0];
  out.proxy.c_m = spec.proxies_bc_m[proxy][1];
  const auto directions = pan::direction_vertices(spec.divisions);
  out.proxy.delay_steps = proxy_delay_steps(spec, proxy);
  std::vector<int> shifts;
  for (int k : spec.shift_steps) shifts.push_back(k - spec.lead_steps);
  const pan::Fitter fitter(spec.radii_m, shifts, spec.length);
  const std::size_t ns = static_cast<std::size_t>(s.n_samples), m = spec.radii_m.size();
  const std::size_t n_fitted = directions.size() * m;
  for (std::size_t f = 0; f < s.fields.size(); ++f) {
    auto& dirs = out.proxy.fields[static_cast<std::size_t>(s.fields[f] - 1)];
    // Every series through the surface, on the solve's own samples.
    const auto& heard = raw.surface_series[f];
    std::vector<float> near(heard.size() * ns);
    for (std::size_t l = 0; l < heard.size(); ++l)
      for (std::size_t k = 0; k < ns; ++k) near[l * ns + k] = static_cast<float>(heard[l].value[k]);
    for (std::size_t d = 0; d < directions.size(); ++d) {
      std::vector<const float*> series;
      for (std::size_t i = 0; i < m; ++i) series.push_back(near.data() + (d * m + i) * ns);
      const auto far = aligned_far_field(spec, raw.far[f][d], out.proxy.delay_steps[d]);
      dirs.push_back(fitter.fit(series, ns, spec.epsilon, out.proxy.delay_steps[d], far));
    }
    out.extra_series.emplace_back(near.begin() + static_cast<std::ptrdiff_t>(n_fitted * ns), near.end());
  }
  return out;
}

}  // namespace clatter::jobs
