#include "banks/pan/solve_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include <memory>

#include "core/errors.hpp"
#include "banks/medium_keys.hpp"
#include "io/mesh.hpp"
#include "kernels/fdtd/dispersion.hpp"
#include "kernels/fdtd/listeners.hpp"

namespace clatter::jobs {

namespace fdtd = kernels::fdtd;

const io::Schema& solve_schema() {
  static const io::Schema schema = [] {
    io::Schema s{"clatter-bank solve: FDTD pulse solves around one rigid ellipsoid or closed mesh", medium_and_pulse_keys()};
    s.keys.insert(s.keys.end(), {
          {"object.kind", std::string("ellipsoid"), "ellipsoid or mesh (rigid body, fields 1-6) or monopole (a "
                                                    "point source at the origin, for absorbing-layer checks)",
           {}, {"ellipsoid", "mesh", "monopole"}},
          {"object.a_m", 0.5, "semi-axis A along x [m]", {0.0, 100.0, true}},
          {"object.b_m", 0.35, "semi-axis B along y [m]", {0.0, 100.0, true}},
          {"object.c_m", 0.2, "semi-axis C along z [m]", {0.0, 100.0, true}},
          {"object.mesh", std::string(""), "kind mesh: a closed, consistently oriented triangle mesh (Wavefront OBJ, "
                                           "coordinates in m, a path relative to the working directory), moved to its "
                                           "centre of mass; rotations turn about it in the mesh's own axes"},
          {"object.scale", 1.0, "kind mesh: factor on the mesh's coordinates", {0.0, 1e4, true}},
          {"grid.dx_m", 0.0065, "cell size [m]; the paper's 6.5 mm keeps the me4 scheme within 2 % at 1 m for "
                                "h = 1e-4 s (docs/fdtd.md, error budget)", {0.0, 10.0, true}},
          {"grid.half_width_m", 1.0, "half width of the domain inside the absorbing layer [m]", {0.0, 1e4, true}},
          {"grid.pml_cells", std::int64_t{6}, "thickness of the perfectly matched layer [cells]; 6 reflect <= -70 dB", {0, 256}},
          {"grid.octant", true, "solve x, y, z >= 0 only, with mirror planes (8x less work); a mesh must be "
                                "mirror-symmetric in x = 0, y = 0 and z = 0 about its centre of mass"},
          {"time.dt_s", 1.0 / 96000.0, "time step [s]; CFL limit dx / (c sqrt 3)", {0.0, 1.0, true}},
          {"time.duration_s", 0.006, "recorded time after t = 0 (the centre of psi) [s]", {0.0, 100.0, true}},
          {"solve.fields", io::RealList{1, 2, 3, 4, 5, 6},
           "rigid-body fields: 1-3 translation along x, y, z; 4-6 rotation about x, y, z", {1, 6}},
          {"listeners.points_m",
           io::RealList{0.8, 0, 0, 0, 0.8, 0, 0, 0, 0.8, 0.6, 0.5, 0.3, -0.6, 0.5, -0.3},
           "listener positions [m], the body centred on the origin (a mesh: on its centre of mass)", {-1e4, 1e4}, {}, 3},
          {"kirchhoff.radius_m", 0.0, "radius of a Kirchhoff surface (a staircase ball of cell faces) around the body; "
                                      "listeners beyond it are heard through it, past the grid's edge too (docs/fdtd.md); "
                                      "0: none", {0.0, 1e4}},
          {"kirchhoff.far_directions", io::RealList{}, "directions (x, y, z; any length) in which to write the far field "
                                                      "R p as R -> infinity, against tau = t - R/c (needs kirchhoff.radius_m)",
           {-1e4, 1e4}, {}, 3},
          {"solver.cut_cell_samples", std::int64_t{16}, "samples per cell edge for cut-cell fractions", {1, 256}},
          {"solver.pml_reflection", 1e-5, "design reflection of the PML grading at normal incidence", {0.0, 1.0, true}},
          {"solver.scheme", std::string("me4"), "update away from the body: me4 (fourth order in space and time, "
                                                "25 points) or srl (the 7-point leapfrog, second order)",
           {}, {"me4", "srl"}},
          {"solver.max_dispersion_error", 0.02, "warn when the predicted dispersion error of the pulse at the farthest "
                                                "listener exceeds this (relative L2)", {0.0, 10.0, true}},
    });
    return s;
  }();
  return schema;
}

SolveParams parse_solve_params(const io::Config& config) {
  SolveParams p;
  p.medium_c_m_s = config.real("medium.c_m_s");
  p.medium_rho_kg_m3 = config.real("medium.rho_kg_m3");
  p.pulse_h_s = config.real("pulse.h_s");
  p.object_kind = config.string("object.kind");
  p.object_a_m = config.real("object.a_m");
  p.object_b_m = config.real("object.b_m");
  p.object_c_m = config.real("object.c_m");
  p.object_mesh = config.string("object.mesh");
  p.object_scale = config.real("object.scale");
  p.grid_dx_m = config.real("grid.dx_m");
  p.grid_half_width_m = config.real("grid.half_width_m");
  p.grid_pml_cells = static_cast<int>(config.integer("grid.pml_cells"));
  p.grid_octant = config.boolean("grid.octant");
  p.time_dt_s = config.real("time.dt_s");
  p.time_duration_s = config.real("time.duration_s");
  p.solve_fields = config.reals("solve.fields");
  const auto& pts = config.reals("listeners.points_m");
  for (std::size_t i = 0; i + 2 < pts.size(); i += 3) p.listeners_points_m.push_back({pts[i], pts[i + 1], pts[i + 2]});
  p.solver_cut_cell_samples = static_cast<int>(config.integer("solver.cut_cell_samples"));
  p.solver_pml_reflection = config.real("solver.pml_reflection");
  p.solver_scheme = config.string("solver.scheme");
  p.solver_max_dispersion_error = config.real("solver.max_dispersion_error");
  p.kirchhoff_radius_m = config.real("kirchhoff.radius_m");
  const auto& far = config.reals("kirchhoff.far_directions");
  for (std::size_t i = 0; i + 2 < far.size(); i += 3) p.kirchhoff_far_directions.push_back({far[i], far[i + 1], far[i + 2]});
  return p;
}

SolveSpec make_solve_spec(const io::Config& config) { return make_solve_spec(parse_solve_params(config)); }

SolveSpec make_solve_spec(const SolveParams& in) {
  SolveSpec spec;
  fdtd::Problem& p = spec.problem;
  p.c_m_s = in.medium_c_m_s;
  p.rho_kg_m3 = in.medium_rho_kg_m3;
  p.h_s = in.pulse_h_s;
  p.dt_s = in.time_dt_s;
  p.cut_cell_samples = in.solver_cut_cell_samples;
  p.pml_reflection = in.solver_pml_reflection;
  const auto scheme = fdtd::scheme_from_name(in.solver_scheme);
  if (!scheme)
    throw InputError(fmt::format("config: key 'solver.scheme' = \"{}\": must be one of me4, srl", in.solver_scheme));
  p.scheme = *scheme;
  const double dx = in.grid_dx_m;
  const bool monopole = in.object_kind == "monopole";
  p.body = {in.object_a_m, in.object_b_m, in.object_c_m};
  if (in.object_kind == "mesh") {
    if (in.object_mesh.empty()) throw InputError("config: key 'object.mesh' is empty: object.kind = \"mesh\" needs an OBJ file");
    auto mesh_error = [&](const std::string& why) {
      return InputError(fmt::format("config: key 'object.mesh' = \"{}\": {}", in.object_mesh, why));
    };
    io::TriangleMesh mesh;
    try {
      mesh = io::read_obj(in.object_mesh);
    } catch (const InputError& e) {
      throw mesh_error(e.what());
    }
    spec.mesh_path = in.object_mesh;
    spec.mesh_hash = io::mesh_hash(mesh);
    spec.mesh_scale = in.object_scale;
    for (auto& v : mesh.vertices_m)
      for (double& x : v) x *= in.object_scale;
    try {
      p.mesh = std::make_shared<const fdtd::MeshBody>(std::move(mesh.vertices_m), std::move(mesh.triangles));
    } catch (const std::invalid_argument& e) {
      throw mesh_error(e.what());
    }
    if (in.grid_octant && !p.mesh->mirror_symmetric())
      throw InputError(fmt::format("config: key 'grid.octant' = true: the mesh '{}' (object.mesh) is not mirror-symmetric "
                                   "in the planes x = 0, y = 0, z = 0 through its centre of mass ({}): set grid.octant = "
                                   "false to solve the full domain",
                                   in.object_mesh,
                                   std::isfinite(p.mesh->mirror_mismatch())
                                       ? fmt::format("sampled lines differ from their mirror images by {:.3g} of its radius",
                                                     p.mesh->mirror_mismatch())
                                       : std::string("a sampled line and its mirror image cross it a different number of times")));
  }

  // Both schemes' limit (docs/fdtd.md): srl's from the checkerboard mode, me4's from
  // 4 lambda^2 - 3 lambda^4 <= 1 at the same mode.
  const double limit = dx / (p.c_m_s * std::sqrt(3.0));
  if (p.dt_s > limit)
    throw InputError(fmt::format("config: key 'time.dt_s' = {}: violates the CFL limit dx / (c sqrt 3) = {:.6g} s "
                                 "(grid.dx_m = {}, medium.c_m_s = {})",
                                 p.dt_s, limit, dx, p.c_m_s));
  const double half = in.grid_half_width_m;
  const int n_half = static_cast<int>(std::ceil(half / dx - 1e-9));
  const int pml = in.grid_pml_cells;
  p.grid.dx_m = dx;
  p.grid.pml = pml;
  p.grid.octant = in.grid_octant;
  const int n = p.grid.octant ? n_half + pml : 2 * (n_half + pml);
  p.grid.n = {n, n, n};
  if (p.mesh) {
    const auto lo = p.mesh->box_lo_m(), hi = p.mesh->box_hi_m();
    for (int a = 0; a < 3; ++a)
      if (std::max(-lo[a], hi[a]) + dx > n_half * dx)
        throw InputError(fmt::format("config: key 'object.mesh' = \"{}\": the mesh (centred on its centre of mass, "
                                     "scale {}) reaches {} m along {} and must lie inside the domain with a cell to "
                                     "spare (grid.half_width_m = {} gives {} cells of {} m)",
                                     in.object_mesh, in.object_scale, std::max(-lo[a], hi[a]), "xyz"[a], half, n_half, dx));
  } else if (!monopole) {
    const std::array<const char*, 3> keys{"object.a_m", "object.b_m", "object.c_m"};
    const std::array<double, 3> r{p.body.a_m, p.body.b_m, p.body.c_m};
    for (int a = 0; a < 3; ++a)
      if (r[a] + dx > n_half * dx)
        throw InputError(fmt::format("config: key '{}' = {}: the ellipsoid must lie inside the domain with a cell to "
                                     "spare (grid.half_width_m = {} gives {} cells of {} m)",
                                     keys[a], r[a], half, n_half, dx));
  }
  if (!monopole) {
    for (double f : in.solve_fields) {
      if (f != std::floor(f)) throw InputError(fmt::format("config: key 'solve.fields' has {}: not a field index 1-6", f));
      spec.fields.push_back(static_cast<int>(f));
    }
    if (spec.fields.empty()) throw InputError("config: key 'solve.fields' is empty: choose fields from 1-6");
  } else {
    spec.fields = {0};
  }

  if (in.listeners_points_m.empty()) throw InputError("config: key 'listeners.points_m' is empty: give at least one point");
  const double body_radius = monopole ? 0.0 : p.solid().bounding_radius_m();
  // The Kirchhoff surface: its inner cells across each face fluid (3 cells off the body's bounding
  // sphere), its outer ones and their images clear of the layer (kernels/fdtd/kirchhoff.hpp).
  const double rs = in.kirchhoff_radius_m;
  if (rs > 0) {
    if (rs < body_radius + 3 * dx)
      throw InputError(fmt::format("config: key 'kirchhoff.radius_m' has {}: must be at least 3 cells ({} m) beyond the "
                                   "body's bounding radius {} m", rs, 3 * dx, body_radius));
    const fdtd::Box interior = p.grid.interior();
    const double room_m = (interior.hi[0] - p.grid.origin(0)) * dx;
    if (rs + 3 * dx > room_m)
      throw InputError(fmt::format("config: key 'kirchhoff.radius_m' has {}: the surface and the 2 cells outside it "
                                   "need {} m, the grid has {} m inside the layer (grid.half_width_m)", rs, rs + 3 * dx, room_m));
    spec.kirchhoff.radius_m = rs;
  }
  spec.i_time_zero = static_cast<int>(std::ceil(2.0 * p.h_s / p.dt_s - 1e-9));
  spec.n_samples = spec.i_time_zero + static_cast<int>(std::ceil(in.time_duration_s / p.dt_s)) + 1;
  for (std::size_t l = 0; l < in.listeners_points_m.size(); ++l) {
    const auto& x = in.listeners_points_m[l];
    if (rs > 0 && std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > surface_outside_m(spec)) {
      if (auto why = surface_listener_problem(spec, x))
        throw InputError(fmt::format("config: key 'listeners.points_m' point {} = [{}, {}, {}]: {}: raise "
                                     "time.duration_s or use kirchhoff.far_directions", l + 1, x[0], x[1], x[2], *why));
      spec.surface_listeners_m.push_back(x);
      continue;
    }
    fdtd::Problem probe = p;
    probe.field = monopole ? 0 : 1;
    if (auto why = fdtd::listener_problem(probe, x))
      throw InputError(fmt::format("config: key 'listeners.points_m' point {} = [{}, {}, {}]: {}", l + 1, x[0], x[1],
                                   x[2], *why));
    spec.listeners_m.push_back(x);
  }
  for (std::size_t d = 0; d < in.kirchhoff_far_directions.size(); ++d) {
    const auto& u = in.kirchhoff_far_directions[d];
    const double norm = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (rs <= 0)
      throw InputError("config: key 'kirchhoff.far_directions' is given without a surface: set kirchhoff.radius_m");
    if (!(norm > 0))
      throw InputError(fmt::format("config: key 'kirchhoff.far_directions' direction {} is zero", d + 1));
    spec.far_directions.push_back({u[0] / norm, u[1] / norm, u[2] / norm});
  }
  // The error budget's dispersion term at the farthest listener, over the distance from the body's
  // bounding sphere (where the body's sound starts; the whole distance for the monopole); beyond
  // the Kirchhoff surface the sound travels exactly, so only the grid's part counts.
  for (const auto& x : spec.listeners_m)
    spec.farthest_m = std::max(spec.farthest_m, std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - body_radius);
  if (!spec.surface_listeners_m.empty()) spec.farthest_m = std::max(spec.farthest_m, surface_outside_m(spec) - body_radius);
  spec.band_edge_hz = fdtd::pulse_band_edge_hz(p.h_s);
  spec.predicted_error = fdtd::worst_dispersion_error(p.scheme, p.courant(), dx, p.c_m_s, p.h_s, spec.farthest_m);
  spec.max_dispersion_error = in.solver_max_dispersion_error;
  return spec;
}

double surface_outside_m(const SolveSpec& spec) { return spec.kirchhoff.radius_m + 2 * spec.problem.grid.dx_m; }

std::optional<std::string> surface_listener_problem(const SolveSpec& spec, const std::array<double, 3>& x) {
  const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  if (r <= surface_outside_m(spec))
    return fmt::format("{:.4g} m from the centre, not beyond the Kirchhoff surface (radius {} m + 2 cells = {:.4g} m)", r,
                       spec.kirchhoff.radius_m, surface_outside_m(spec));
  const bool monopole = spec.fields.size() == 1 && spec.fields.front() == 0;
  const double body_radius = monopole ? 0.0 : spec.problem.solid().bounding_radius_m();
  const double arrival_s = (r - body_radius) / spec.problem.c_m_s;
  const double record_s = (spec.n_samples - 1 - spec.i_time_zero) * spec.problem.dt_s;
  if (arrival_s >= record_s)
    return fmt::format("the sound arrives there {:.4g} s after the pulse, after the record's {:.4g} s", arrival_s, record_s);
  return std::nullopt;
}

}  // namespace clatter::jobs
