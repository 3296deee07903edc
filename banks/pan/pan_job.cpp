#include "banks/pan/pan_job.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/progress.hpp"
#include "core/stage_log.hpp"
#include "io/scene.hpp"
#include "kernels/fdtd/listeners.hpp"
#include "kernels/pan/directions.hpp"
#include "kernels/pan/field.hpp"
#include "kernels/pan/fit.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {

namespace pan = kernels::pan;

model::PanHeldOut check_held_out(const PanSpec& spec, const model::PanBankHeader& header, const model::PanProxy& built,
                                 int field, const std::vector<std::array<double, 3>>& points, const std::vector<float>& raw) {
  Stage stage("held-out check");
  model::PanProxy stored;
  stored.b_m = built.b_m;
  stored.c_m = built.c_m;
  stored.mesh = built.mesh;
  for (int o = 0; o < built.octants(); ++o) stored.field(field, o) = io::stored_field(header, built.field(field, o));
  const std::size_t ns = static_cast<std::size_t>(spec.solve.n_samples);
  model::PanHeldOut out;
  for (std::size_t l = 0; l < points.size(); ++l) {
    const float* series = raw.data() + l * ns;
    double e = 0;
    for (std::size_t k = 0; k < ns; ++k) e += double{series[k]} * series[k];
    out.points_m.push_back(points[l]);
    out.error.push_back(held_out_error(spec, header, stored, field, points[l], series));
    out.raw_l2.push_back(std::sqrt(e));
  }
  return out;
}

void read_scene_meshes(PanParams& params) {
  if (params.objects_scene.empty()) return;
  const io::Scene scene = io::read_scene(params.objects_scene, false);
  params.scene_objects = scene.objects.size();
  for (const io::SceneObject& o : scene.objects)
    if (!o.mesh_path.empty()) params.scene_meshes.push_back({o.mesh_path, o.where});
}

TaskWriter run_pan_task(MPI_Comm group, const PanSpec& spec, const PanTask& task, double progress_interval_s) {
  PanSpec one = spec;
  one.solve.fields = one.solve_full.fields = {task.field};
  const auto points = held_out_points(spec, task.proxy);
  auto result = build_proxy(group, one, task.proxy, points, progress_interval_s);
  if (mpi::rank(group) != 0) return {};
  const auto header = pan_header(spec);
  model::PanTaskResult r;
  r.proxy = static_cast<std::uint32_t>(task.proxy);
  r.b_m = result.proxy.b_m;
  r.c_m = result.proxy.c_m;
  r.mesh = result.proxy.mesh;
  r.field = task.field;
  r.held_out_points_m = points;
  r.held_out_raw = std::move(result.extra_series.at(0));
  r.fit = std::move(result.proxy.field(task.field));
  for (int o = 1; o < result.proxy.octants(); ++o) r.other_fits[static_cast<std::size_t>(o - 1)] = std::move(result.proxy.field(task.field, o));
  return [r = std::move(r), header](io::File& file, const std::string& group_name) {
    io::write_pan_task(file, group_name, r, header.lattice(), header.values());
  };
}

model::PanBank merge_pan_results(const PanSpec& spec, const std::string& results_dir, const std::string& config_toml) {
  model::PanBank bank;
  bank.header = pan_header(spec);
  for (const auto& body : spec.bodies) bank.proxies.push_back(body.entry());
  const auto tasks = pan_tasks(spec);
  bank.sweep.sweep_id = io::sweep_id(config_toml);
  bank.sweep.tasks_total = static_cast<std::uint32_t>(tasks.size());
  for (const auto& t : tasks) {
    const std::string label = fmt::format("{} {}, field {}", t.name, spec.bodies[t.proxy].label(), t.field);
    if (!task_done(results_dir, t.name, label, config_toml, bank.sweep)) continue;
    auto file = io::File::open(io::task_path(results_dir, t.name));
    auto r = io::read_pan_task(file, "/result", bank.header);
    if (r.proxy != t.proxy || r.field != t.field)
      throw InputError(fmt::format("{}: holds proxy {} field {}, expected {} field {}", file.path(), r.proxy, r.field,
                                   t.proxy, t.field));
    if (r.mesh != bank.proxies[t.proxy].mesh)
      throw InputError(fmt::format("{}: was solved around another body than {} (its mesh key '{}', scale {})", file.path(),
                                   spec.bodies[t.proxy].label(), r.mesh.key, r.mesh.scale));
    auto& proxy = bank.proxies[t.proxy];
    for (int o = 0; o < proxy.octants(); ++o) {
      model::PanField& fit = o == 0 ? r.fit : r.other_fits[static_cast<std::size_t>(o - 1)];
      try {  // the replay io cannot do (kernels/pan/direction_mesh.hpp)
        if (pan::DirectionMesh(bank.header.divisions, bank.header.max_levels, fit.directions).size() != fit.terms.size())
          throw std::invalid_argument("not one set of terms per direction");
      } catch (const std::invalid_argument& e) {
        throw InputError(fmt::format("{}: its direction set{} is not a refinement of the octant with fit.divisions = {} "
                                     "and fit.direction_levels = {}: {}", file.path(), o > 0 ? fmt::format(" of octant {}", o) : "",
                                     spec.divisions, spec.direction_levels, e.what()));
      }
      proxy.field(t.field, o) = std::move(fit);
    }
    if (r.held_out_points_m != held_out_points(spec, t.proxy) ||
        r.held_out_raw.size() != r.held_out_points_m.size() * static_cast<std::size_t>(spec.solve.n_samples))
      throw InputError(fmt::format("{}: its held-out points or series are not this config's (check.held_out_*), or the task "
                                   "was solved by an older clatter-bank, which drew them by the entry's place in the list: "
                                   "remove the file to solve the task again", file.path()));
    proxy.held_out[static_cast<std::size_t>(t.field - 1)] =
        check_held_out(spec, bank.header, proxy, t.field, r.held_out_points_m, r.held_out_raw);
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
  const PanBody& body = spec.bodies[proxy];
  const double delay =
      pan::support_delay_samples(d, spec.a_m, body.b_m, body.c_m, body.shape, spec.solve.problem.c_m_s, dt);
  const int whole = static_cast<int>(std::floor(delay));
  return {whole, -(delay - whole) * dt};
}

double l2(const std::vector<double>& x) {
  double e = 0;
  for (double v : x) e += v * v;
  return std::sqrt(e);
}

// The miss floor from the strongest far field among the layout's directions: 1.5 % of its
// amplitude (2e-4 of its energy). The held-out check holds every listener to 5 % of its own field,
// down to where a field is weak; at a tenth, the cigar's swing about z missed by 6.4 % 1.2 degrees
// off its zero plane (docs/pan.md, "The refinement's floor"); at 1.5 % it holds 2.8 %, and
// fields strong in every direction refine exactly as before.
double floor_from_strongest(double strongest_l2) { return 0.015 * strongest_l2; }

// Hearing a task's directions takes minutes on its group's rank 0 alone: it polls SIGTERM and
// SIGINT per far field and per direction, and run_solve stops the group together.
void stop_if_interrupted() {
  if (interrupt_requested()) throw Interrupted("interrupted while hearing through the Kirchhoff surface");
}

void add_strength(FarFieldStrength& s, double l2) {
  s.strongest_l2 = std::max(s.strongest_l2, l2);
  s.energy += l2 * l2;
}

}  // namespace

ProxyResult build_proxy(MPI_Comm comm, const PanSpec& spec, std::size_t proxy,
                        const std::vector<std::array<double, 3>>& extra_listeners_m, double progress_interval_s) {
  namespace fdtd = kernels::fdtd;
  const PanBody& body = spec.bodies[proxy];
  SolveSpec s = body.shape.octants == 8 ? spec.solve_full : spec.solve;  // no mirror symmetry: the full domain
  s.problem.body = {spec.a_m, body.b_m, body.c_m};
  s.problem.mesh = body.mesh;  // a mesh entry's, normalized
  s.kirchhoff = kirchhoff_shape(spec, body);
  if (body.mesh) {             // for the solve's log
    s.mesh_path = body.source;
    s.mesh_hash = body.shape.key;
    s.mesh_scale = body.shape.scale;
  }
  // make_pan_spec checked the radii; the extra listeners are new, heard through the Kirchhoff
  // surface like them, anywhere outside it.
  for (std::size_t l = 0; l < extra_listeners_m.size(); ++l)
    if (auto why = surface_listener_problem(s, extra_listeners_m[l]))
      throw InputError(fmt::format("extra listener {} for {}: {}", l + 1, body.label(), *why));
  ProxyResult out;
  out.proxy = body.entry();
  std::vector<int> shifts;
  for (int k : spec.shift_steps) shifts.push_back(k - spec.lead_steps);
  const pan::Fitter fitter(spec.radii_m, shifts, spec.length);
  const std::size_t ns = static_cast<std::size_t>(s.n_samples), m = spec.radii_m.size();
  // The yardstick of a field's refinement floor (refine_directions): field 3, translation along the
  // smallest semi-axis C, which radiates the most of the translations (the largest projected
  // area, A B). Solved first, and only heard for its strength when it is not one of the fields.
  const std::vector<int> wanted = s.fields;
  const bool yardstick = spec.direction_tolerance > 0;
  if (yardstick) {
    s.fields.erase(std::remove(s.fields.begin(), s.fields.end(), 3), s.fields.end());
    s.fields.insert(s.fields.begin(), 3);
  }
  const bool store_3 = std::find(wanted.begin(), wanted.end(), 3) != wanted.end();
  out.extra_series.resize(wanted.size());
  FarFieldStrength field_3;
  // Rank 0, per field, while its surface is alive: the field's direction set (refined where the
  // far field asks for it), then every direction heard at its radii and at infinity, aligned by its
  // support distance (the whole steps in the fit, the fraction here).
  const int octants = body.shape.octants;
  // The octants heard: all but those across the mesh's mirror planes (PanBody::mirrored_axes),
  // whose fields are the heard ones' mirror images; their strengths are the heard ones' too.
  std::vector<int> heard_octants;
  for (int o = 0; o < octants; ++o)
    if ((o & body.mirrored_axes) == 0) heard_octants.push_back(o);
  const double heard_count = static_cast<double>(heard_octants.size());
  auto hear = [&](std::size_t fi, const fdtd::SurfaceField& surface) {
    const int f = s.fields[fi];
    // An entry of eight octants: field 3's strength over all of them, an octant's mean.
    auto strength_of_3 = [&] {
      FarFieldStrength mean;
      for (const int o : heard_octants) {
        const FarFieldStrength one = layout_strength(spec, proxy, surface, o);
        mean.strongest_l2 = std::max(mean.strongest_l2, one.strongest_l2);
        mean.energy += one.energy / heard_count;
      }
      return mean;
    };
    if (yardstick && f == 3 && !store_3) {
      field_3 = strength_of_3();
      return;
    }
    // A rotation field per unit angular acceleration moves the surface by up to A.
    const double per_unit = f <= 3 ? 1.0 : spec.a_m;
    std::vector<std::vector<float>> near(m, std::vector<float>(ns));
    std::vector<const float*> series;
    for (const auto& v : near) series.push_back(v.data());
    FarFieldStrength strength_3;
    // Hearing is most of a task's time (docs/pan.md "Cost"): its progress, like the time loop's.
    ProgressTimer progress(progress_interval_s);
    for (const int o : heard_octants) {
      auto& field = out.proxy.field(f, o);
      const DirectionRefinement set =
          spec.direction_tolerance > 0
              ? refine_directions(spec, proxy, surface, spec.direction_tolerance, spec.direction_levels, spec.max_directions,
                                  per_unit * per_unit * field_3.energy, o)
              : DirectionRefinement{pan::uniform_mesh(spec.divisions, spec.direction_levels), 0, {}, {}};
      strength_3.strongest_l2 = std::max(strength_3.strongest_l2, set.strength.strongest_l2);
      strength_3.energy += set.strength.energy / heard_count;
      if (!set.radiated)
        spdlog::info("pan: {}, field {}{}: {:.2g} of the yardstick's energy over the layout: {}", body.label(), f,
                     octants == 8 ? fmt::format(" octant {}", o + 1) : std::string(),
                     set.strength.energy / std::max(per_unit * per_unit * field_3.energy, 1e-300),
                     set.silent ? "the solve's noise, stored with no coefficients (silence)"
                                : "not radiated, left at the layout's directions");
      if (set.silent) {  // noise, not worth a byte: kept as no coefficients
        field.terms.assign(set.mesh.size(), model::SparseTerms{});
        field.directions = set.mesh.stored();
        continue;
      }
      for (std::size_t v = 0; v < set.mesh.size(); ++v) {
        stop_if_interrupted();
        if (progress.due()) {
          const double nth = static_cast<double>(std::find(heard_octants.begin(), heard_octants.end(), o) - heard_octants.begin());
          const double done = (nth + static_cast<double>(v) / static_cast<double>(set.mesh.size())) / heard_count;
          spdlog::info("pan: {}, field {}: hearing direction {}/{}{} at {} radii and infinity{}", body.label(), f, v + 1,
                       set.mesh.size(), octants == 8 ? fmt::format(" of octant {} ({}/{} heard)", o + 1, nth + 1, heard_count) : std::string(), m,
                       done > 0 ? fmt::format(", ETA {:.0f} s", progress.eta_s(done)) : std::string());
        }
        // Stored over the field's symmetry zeros (kernels/pan/directions.hpp), heard off the planes;
        // an entry of eight octants as it is, in the octant's own direction.
        const auto d = heard_direction(spec, proxy, f, o, set.mesh.direction(v));
        const double zeros = octants == 8 ? 1.0 : pan::symmetry_zeros(f, d);
        const Alignment a = alignment(spec, proxy, d);
        std::vector<std::array<double, 3>> points;
        for (const double r : spec.radii_m) points.push_back({r * d[0], r * d[1], r * d[2]});
        const auto heard_at = fdtd::pressure_at(surface, points, a.advance_s);  // one pass per few radii
        for (std::size_t i = 0; i < m; ++i)
          for (std::size_t k = 0; k < ns; ++k) near[i][k] = static_cast<float>(heard_at[i].value[k] / zeros);
        const auto heard = set.far_fields.find(pan::lattice_key(set.mesh.vertices()[v]));
        field.terms.push_back(fitter.fit(series, ns, spec.epsilon, a.whole_steps,
                                         heard != set.far_fields.end()
                                             ? heard->second
                                             : stored_far_field(spec, proxy, surface, set.mesh.direction(v), o)));
      }
      field.directions = set.mesh.stored();
    }
    // The octants across the mirror planes: the same directions (each mirrored), the field's
    // coefficients times its parity across each plane crossed.
    for (int o = 0; o < octants; ++o) {
      const int across = o & body.mirrored_axes;
      if (across == 0) continue;
      double sign = 1;
      for (int a = 0; a < 3; ++a)
        if (across & (1 << a)) sign *= fdtd::field_parity(f, a);
      auto& field = out.proxy.field(f, o);
      field = out.proxy.field(f, o & ~across);
      if (sign < 0)
        for (auto& t : field.terms)
          for (float& x : t.value) x = -x;
    }
    if (f == 3) field_3 = strength_3;
    std::vector<float> extra(extra_listeners_m.size() * ns);
    const auto heard_extra = fdtd::pressure_at(surface, extra_listeners_m);
    for (std::size_t l = 0; l < extra_listeners_m.size(); ++l)
      for (std::size_t k = 0; k < ns; ++k) extra[l * ns + k] = static_cast<float>(heard_extra[l].value[k]);
    const auto slot = std::find(wanted.begin(), wanted.end(), f) - wanted.begin();  // in the caller's order
    out.extra_series[static_cast<std::size_t>(slot)] = std::move(extra);
  };
  run_solve(comm, s, progress_interval_s, hear);
  if (mpi::rank(comm) != 0) return {};
  return out;
}

std::vector<std::vector<double>> aligned_far_fields(const PanSpec& spec, std::size_t proxy,
                                                    const kernels::fdtd::SurfaceField& surface,
                                                    const std::vector<std::array<double, 3>>& d) {
  std::vector<Alignment> a;
  std::vector<kernels::fdtd::FarListener> listeners;
  for (const auto& x : d) {
    a.push_back(alignment(spec, proxy, x));
    listeners.push_back({x, a.back().advance_s});
  }
  const auto heard = kernels::fdtd::far_field(surface, listeners);  // in one pass per few directions
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < d.size(); ++i) out.push_back(frame_far_field(spec, heard[i], a[i].whole_steps));
  return out;
}

std::vector<double> aligned_far_field(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                      const std::array<double, 3>& d) {
  return std::move(aligned_far_fields(spec, proxy, surface, {d}).front());
}

std::array<double, 3> heard_direction(const PanSpec& spec, std::size_t proxy, int field, int octant,
                                      const std::array<double, 3>& d) {
  return spec.bodies[proxy].shape.octants == 8 ? model::in_octant(d, octant) : pan::off_planes(field, d);
}

std::vector<std::vector<double>> stored_far_fields(const PanSpec& spec, std::size_t proxy,
                                                   const kernels::fdtd::SurfaceField& surface,
                                                   const std::vector<std::array<double, 3>>& d, int octant) {
  std::vector<std::array<double, 3>> heard;
  for (const auto& x : d) heard.push_back(heard_direction(spec, proxy, surface.field, octant, x));
  auto q = aligned_far_fields(spec, proxy, surface, heard);
  if (spec.bodies[proxy].shape.octants == 8) return q;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double zeros = pan::symmetry_zeros(surface.field, heard[i]);
    for (double& x : q[i]) x /= zeros;
  }
  return q;
}

std::vector<double> stored_far_field(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                     const std::array<double, 3>& d, int octant) {
  return std::move(stored_far_fields(spec, proxy, surface, {d}, octant).front());
}

FarFieldStrength layout_strength(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                 int octant) {
  FarFieldStrength s;
  std::vector<std::array<double, 3>> d;
  for (const auto& v : pan::direction_vertices(spec.divisions)) d.push_back(model::in_octant(v, octant));
  for (const auto& q : aligned_far_fields(spec, proxy, surface, d)) add_strength(s, l2(q));
  return s;
}

double far_field_floor(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface) {
  return floor_from_strongest(layout_strength(spec, proxy, surface).strongest_l2);
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
                                      double tolerance, int max_levels, std::size_t max_vertices,
                                      double yardstick_energy, int octant) {
  DirectionRefinement out{pan::uniform_mesh(spec.divisions, max_levels), 0, {}, {}};
  auto& mesh = out.mesh;
  // The true far fields, heard a few directions per pass over the surface as the refinement asks.
  auto ahead = [&](const std::vector<pan::LatticePoint>& points) {
    std::vector<pan::LatticePoint> wanted;
    std::vector<std::array<double, 3>> d;
    for (const auto& p : points)
      if (!out.far_fields.count(pan::lattice_key(p)) &&
          std::none_of(wanted.begin(), wanted.end(), [&](const auto& w) { return pan::lattice_key(w) == pan::lattice_key(p); })) {
        wanted.push_back(p);
        d.push_back(mesh.direction(p));
      }
    if (wanted.empty()) return;
    stop_if_interrupted();
    auto q = stored_far_fields(spec, proxy, surface, d, octant);
    for (std::size_t i = 0; i < wanted.size(); ++i) out.far_fields.emplace(pan::lattice_key(wanted[i]), std::move(q[i]));
  };
  auto at = [&](const pan::LatticePoint& p) -> const std::vector<double>& {
    ahead({p});
    return out.far_fields.at(pan::lattice_key(p));
  };
  ahead(mesh.vertices());
  // The unrefined mesh is the layout: the field's strength there (of p = q x its symmetry zeros)
  // and the strongest q, which set the floor below.
  double strongest_q = 0;
  for (const auto& v : mesh.vertices()) {
    const double q = l2(at(v));
    strongest_q = std::max(strongest_q, q);
    add_strength(out.strength, spec.bodies[proxy].shape.octants == 8 ? q : q * pan::symmetry_zeros(surface.field, mesh.direction(v)));
  }
  // Not radiated: left at the layout; far below it, the solve's noise (stored empty, build_proxy).
  if (out.strength.energy < kRadiatedEnergy * yardstick_energy) {
    out.radiated = false;
    out.silent = out.strength.energy < kSilentEnergy * yardstick_energy;
    return out;
  }
  // A miss counts where q is strong and where p = q Z_f, what a listener hears, is: the floor is
  // the smaller of floor_from_strongest of q and that of p over Z_f here. With
  // the q floor alone, q's peaks near the planes (where Z_f is small) set it, and a direction where
  // p is strong but q is not, the cigar's swing at 45 degrees off its axis, was taken as converged
  // while its far field missed by 10 % (docs/pan.md, "The refinement's floor").
  const double floor_q = floor_from_strongest(strongest_q), floor_p = floor_from_strongest(out.strength.strongest_l2);
  const bool mirrored = spec.bodies[proxy].shape.octants != 8;
  std::vector<double> sum(spec.length);
  auto miss = [&](const pan::LatticePoint& p, const pan::DirectionWeights& w) {
    pan::blend(w, [&](std::size_t v) -> const std::vector<double>& { return at(mesh.vertices()[v]); }, sum);
    const double zeros =
        mirrored ? pan::symmetry_zeros(surface.field, heard_direction(spec, proxy, surface.field, octant, mesh.direction(p))) : 1.0;
    return far_field_miss(sum, at(p), std::min(floor_q, floor_p / zeros));
  };
  out.splits = pan::refine(mesh, miss, tolerance, max_vertices, ahead);
  return out;
}

double held_out_error(const PanSpec& spec, const model::PanBankHeader& header, const model::PanProxy& proxy, int field,
                      const std::array<double, 3>& x_m, const float* raw, pan::Interpolation interpolation) {
  const auto s = pan::evaluate({&header, &proxy, field}, x_m, 1.0, 0.0, interpolation);
  const std::size_t ns = static_cast<std::size_t>(spec.solve.n_samples);
  const double dt = spec.solve.problem.dt_s;
  // PAN sample k is at t0 + k dt; raw sample k at (k - i_time_zero) dt. Rounding the offset to a
  // sample instead cost up to 5 % on field 4 of an elongated proxy.
  const double offset = (s.t0_s + spec.solve.i_time_zero * dt) / dt;
  const long whole = static_cast<long>(std::floor(offset));
  const double frac = offset - static_cast<double>(whole);  // raw sample k = PAN index k - whole - frac
  auto pan_at = [&](long j) { return j >= 0 && j < static_cast<long>(s.p.size()) ? s.p[static_cast<std::size_t>(j)] : 0.0; };
  const double x = 1.0 - frac;  // PAN index k - whole - 1 + x
  const std::array<double, 4> w{-x * (x - 1) * (x - 2) / 6, (x + 1) * (x - 1) * (x - 2) / 2, -(x + 1) * x * (x - 2) / 2,
                                (x + 1) * x * (x - 1) / 6};
  double num = 0, den = 0;
  for (std::size_t k = 0; k < ns; ++k) {
    const long j = static_cast<long>(k) - whole - 1;
    const double p = w[0] * pan_at(j - 1) + w[1] * pan_at(j) + w[2] * pan_at(j + 1) + w[3] * pan_at(j + 2);
    num += (p - raw[k]) * (p - raw[k]);
    den += double{raw[k]} * raw[k];
  }
  return std::sqrt(num / den);
}

}  // namespace clatter::jobs
