#include "banks/pan/pan_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "banks/medium_keys.hpp"
#include "kernels/fdtd/mesh_body.hpp"
#include "kernels/mass_properties.hpp"
#include "kernels/fdtd/problem.hpp"
#include "kernels/pan/directions.hpp"
#include "kernels/pan/fit.hpp"
#include "kernels/pan/wavelet.hpp"

namespace clatter::jobs {

namespace pan = kernels::pan;

// Far beyond a useful bank (the paper's grid has 66 proxies), far below exhausting memory.
constexpr double kMaxProxies = 1e5;

namespace {

// The proxy grid's keys: pan's alone (pan-object's entries are meshes).
bool proxy_grid_key(const std::string& key) { return key == "proxies.grid_min_m" || key == "proxies.grid_step_m" || key == "proxies.list_m"; }

}  // namespace

const io::Schema& pan_schema() {
  static const io::Schema schema = [] {
    io::Schema s{"clatter-bank pan: the PAN proxy bank (FDTD solves, wavelet fit, compression)", medium_and_pulse_keys()};
    // The defaults are the paper's bank (Chadwick et al. 2012, section 5), the one users should build;
    // configs/pan-demo.toml is the small fast one.
    s.keys.insert(s.keys.end(), {
        {"proxies.a_m", 0.5, "semi-axis A of every proxy [m]; pan-object: the radius every mesh is scaled to",
         {0.0, 100.0, true}},
        {"proxies.grid_min_m", 0.025, "smallest B and C of the proxy grid [m]", {0.0, 100.0, true}},
        {"proxies.grid_step_m", 0.0475, "step of B and C in the proxy grid [m]", {0.0, 100.0, true}},
        {"proxies.list_m", io::RealList{}, "explicit (B, C) proxies [m]; when given, replaces the grid", {0.0, 100.0},
         {}, 2},
        {"grid.dx_m", 0.0065, "cell size [m]", {0.0, 10.0, true}},
        {"grid.pml_cells", std::int64_t{6}, "thickness of the perfectly matched layer [cells]", {0, 256}},
        {"time.dt_s", 1.0 / 96000.0, "time step = PAN sample interval [s]; CFL limit dx / (c sqrt 3)", {0.0, 1.0, true}},
        {"time.tail_s", 0.012, "recorded time after the pulse reaches the farthest radius [s]", {0.0, 10.0, true}},
        {"solve.fields", io::RealList{1, 2, 3, 4, 5, 6}, "rigid-body fields to solve and store", {1, 6}},
        {"fit.radii_m", io::RealList{0.7, 0.775, 0.85, 1.0, 1.2, 1.5, 2.0, 3.0, 5.0},
         "the M stored radii [m], ascending, outside the Kirchhoff surface (A + 3 cells); rounded to whole steps of "
         "c dt. R p is interpolated in 1/R between them and the far field (docs/pan.md, \"The radial model\")",
         {0.0, 1e4, true}},
        {"fit.divisions", std::int64_t{8}, "the layout every field's directions start from: octant edges cut in d (2, "
                                           "4, 8, 16, 32 or 64), (d+1)(d+2)/2 directions; 8: the paper's 45", {2, 64}},
        {"fit.direction_tolerance", 0.04, "refine each field's directions where quadratic interpolation of its far "
                                          "field between them misses it by more than this (relative L2) at a split "
                                          "point; 0: the layout of fit.divisions only (docs/pan.md, \"Adaptive "
                                          "directions\")", {0.0, 1.0}},
        {"fit.direction_levels", std::int64_t{3}, "splits at most below an element of the layout (each quarters "
                                                  "its size)", {0, 8}},
        {"fit.max_directions", std::int64_t{2500}, "stop refining a field at this many directions", {3, 100000}},
        {"fit.epsilon", 0.01, "keep wavelet coefficient j iff |p^_i^j| >= epsilon ||p^_i||_inf at some radius i or at infinity (the far field)", {0.0, 1.0}},
        {"check.held_out_directions", std::int64_t{8}, "random directions per proxy (inside the octant, none a "
                                                       "stored one) where each task checks its field as the bank stores "
                                                       "it against the raw solve, at check.held_out_radii_m "
                                                       "(clatter-bank info prints the result); 0: no check", {0, 1000}},
        {"check.held_out_radii_m", io::RealList{}, "the radii of that check [m], outside the Kirchhoff surface; "
                                                   "rounded to whole steps of c dt; empty: the geometric mean of each "
                                                   "pair of neighbouring fit.radii_m", {0.0, 1e4, true}},
        {"solver.cut_cell_samples", std::int64_t{16}, "samples per cell edge for cut-cell fractions", {1, 256}},
        {"solver.scheme", std::string("me4"), "update away from the body: me4 (fourth order in space and time, "
                                              "25 points) or srl (the 7-point leapfrog, second order)",
         {}, {"me4", "srl"}},
        {"solver.max_dispersion_error", 0.02, "warn when the predicted dispersion error of the pulse at the farthest "
                                              "radius exceeds this (relative L2)", {0.0, 10.0, true}},
    });
    return s;
  }();
  return schema;
}

const io::Schema& pan_object_schema() {
  static const io::Schema schema = [] {
    io::Schema s{"clatter-bank pan-object: the PAN bank of given closed meshes, one entry each (000 section 5's "
                 "per-object PAN; the same solve, directions and fit as a proxy's)", {}};
    for (const auto& key : pan_schema().keys)
      if (!proxy_grid_key(key.name)) s.keys.push_back(key);
    s.keys.push_back({"objects.meshes", io::StringList{}, "closed, consistently oriented triangle meshes (OBJ, metres), "
                                                          "one entry each, keyed by io::mesh_hash; each is moved to its "
                                                          "centre of mass and scaled to bounding radius proxies.a_m; one "
                                                          "mirror-symmetric in the planes through it is solved in the "
                                                          "octant (one octant of directions per field, as a proxy), any "
                                                          "other in the full domain (8x the cells, eight octants of "
                                                          "directions)"});
    s.keys.push_back({"objects.scene", std::string(""), "a scene (docs/scene-format.md): every object given by a mesh "
                                                        "too, each mesh once (debris shares meshes)"});
    s.keys.push_back({"objects.all_octants", false, "solve every mesh in the full domain with eight octants of "
                                                    "directions, each heard, a mirror-symmetric one too (8x the cells "
                                                    "and series: a check of the symmetry)"});
    return s;
  }();
  return schema;
}

namespace {

// The keys both kinds share.
void parse_shared_params(const io::Config& config, PanParams& p) {
  p.medium_c_m_s = config.real("medium.c_m_s");
  p.medium_rho_kg_m3 = config.real("medium.rho_kg_m3");
  p.pulse_h_s = config.real("pulse.h_s");
  p.proxies_a_m = config.real("proxies.a_m");
  p.grid_dx_m = config.real("grid.dx_m");
  p.grid_pml_cells = static_cast<int>(config.integer("grid.pml_cells"));
  p.time_dt_s = config.real("time.dt_s");
  p.time_tail_s = config.real("time.tail_s");
  p.solve_fields = config.reals("solve.fields");
  p.fit_radii_m = config.reals("fit.radii_m");
  p.fit_divisions = static_cast<int>(config.integer("fit.divisions"));
  p.fit_direction_tolerance = config.real("fit.direction_tolerance");
  p.fit_direction_levels = static_cast<int>(config.integer("fit.direction_levels"));
  p.fit_max_directions = static_cast<int>(config.integer("fit.max_directions"));
  p.fit_epsilon = config.real("fit.epsilon");
  p.check_held_out_directions = static_cast<int>(config.integer("check.held_out_directions"));
  p.check_held_out_radii_m = config.reals("check.held_out_radii_m");
  p.solver_cut_cell_samples = static_cast<int>(config.integer("solver.cut_cell_samples"));
  p.solver_scheme = config.string("solver.scheme");
  p.solver_max_dispersion_error = config.real("solver.max_dispersion_error");
}

}  // namespace

PanParams parse_pan_params(const io::Config& config) {
  PanParams p;
  parse_shared_params(config, p);
  p.proxies_grid_min_m = config.real("proxies.grid_min_m");
  p.proxies_grid_step_m = config.real("proxies.grid_step_m");
  const auto& list = config.reals("proxies.list_m");
  for (std::size_t i = 0; i + 1 < list.size(); i += 2) p.proxies_list_m.push_back({list[i], list[i + 1]});
  return p;
}

PanParams parse_pan_object_params(const io::Config& config) {
  PanParams p;
  parse_shared_params(config, p);
  p.objects_meshes = config.strings("objects.meshes");
  p.objects_scene = config.string("objects.scene");
  p.objects_all_octants = config.boolean("objects.all_octants");
  if (p.objects_meshes.empty() && p.objects_scene.empty())
    throw InputError("config: key 'objects.meshes' is empty and no objects.scene: a pan-object bank needs at least one mesh");
  return p;
}

PanSpec make_pan_spec(const io::Config& config) { return make_pan_spec(parse_pan_params(config)); }

namespace {

// The (B, C) proxies: the explicit list, or the grid C <= B <= A.
std::vector<std::array<double, 2>> proxy_list(const PanParams& in) {
  if (!in.proxies_list_m.empty()) return in.proxies_list_m;
  std::vector<std::array<double, 2>> out;
  const double lo = in.proxies_grid_min_m, step = in.proxies_grid_step_m;
  // Refused before building: a fine step would otherwise exhaust memory (found by fuzz_config).
  const double n_values = std::floor((in.proxies_a_m * (1 + 1e-12) - lo) / step) + 1;
  if (n_values * (n_values + 1) / 2 > kMaxProxies)
    throw InputError(fmt::format("config: key 'proxies.grid_step_m' has {}: the grid from proxies.grid_min_m = {} to "
                                 "proxies.a_m = {} would hold {:.3g} proxies, more than {}",
                                 step, lo, in.proxies_a_m, n_values * (n_values + 1) / 2, kMaxProxies));
  std::vector<double> values;
  for (int i = 0; lo + i * step <= in.proxies_a_m * (1 + 1e-12); ++i) values.push_back(lo + i * step);
  for (std::size_t b = 0; b < values.size(); ++b)
    for (std::size_t c = 0; c <= b; ++c) out.push_back({values[b], values[c]});
  return out;
}

// The Kirchhoff surface's ball: three cells off the bounding sphere, so that the cells across its
// faces are fluid (kernels/fdtd/kirchhoff.hpp). kirchhoff_shape cuts it per body.
double kirchhoff_radius_m(const PanSpec& spec, double dx_m) { return spec.a_m + 3 * dx_m; }

// One proxy's solve: octant mode (the bank stores the positive octant; eqs. 16-21 give the rest),
// a sphere of radius A (build_proxy sets the body per proxy). Every listener is heard through the
// Kirchhoff surface (make_pan_spec), so the grid need only hold the surface; one listener just
// outside it keeps the solve's error budget and health check.
SolveParams proxy_solve_params(const PanParams& in, const PanSpec& spec) {
  const double r_max = spec.radii_m.back();
  SolveParams s = parse_solve_params(io::Config(solve_schema()));  // the solve's defaults for the rest
  s.medium_c_m_s = in.medium_c_m_s;
  s.medium_rho_kg_m3 = in.medium_rho_kg_m3;
  s.pulse_h_s = in.pulse_h_s;
  s.grid_dx_m = in.grid_dx_m;
  // Room for the listener's tricubic stencil (2 cells) and, for me4, the blend into the layer (an
  // unknown scheme is make_solve_spec's error).
  const auto scheme = kernels::fdtd::scheme_from_name(in.solver_scheme).value_or(kernels::fdtd::Scheme::srl);
  const int margin_cells = 3 + kernels::fdtd::blend_cells(scheme, in.grid_pml_cells);
  const double rs = kirchhoff_radius_m(spec, in.grid_dx_m);
  s.grid_half_width_m = rs + (margin_cells + 2) * in.grid_dx_m;
  s.grid_pml_cells = in.grid_pml_cells;
  s.grid_octant = true;
  s.time_dt_s = in.time_dt_s;
  s.time_duration_s = r_max / in.medium_c_m_s + in.time_tail_s;  // the outermost radius hears the whole tail
  s.object_a_m = s.object_b_m = s.object_c_m = spec.a_m;
  s.solver_cut_cell_samples = in.solver_cut_cell_samples;
  s.solver_scheme = in.solver_scheme;
  s.solver_max_dispersion_error = in.solver_max_dispersion_error;
  s.solve_fields = in.solve_fields;
  s.listeners_points_m = {{rs + 2 * in.grid_dx_m, 0.0, 0.0}};
  return s;
}

}  // namespace

kernels::fdtd::SurfaceShape kirchhoff_shape(const PanSpec& spec, const PanBody& body) {
  const double dx = spec.solve.problem.grid.dx_m;
  kernels::fdtd::SurfaceShape shape;
  shape.radius_m = kirchhoff_radius_m(spec, dx);
  std::array<double, 3> half{spec.a_m, body.b_m, body.c_m};
  if (body.mesh) {
    const auto lo = body.mesh->box_lo_m(), hi = body.mesh->box_hi_m();
    for (int a = 0; a < 3; ++a) half[a] = std::max(-lo[a], hi[a]);
  }
  // Four cells, one more than the ball's three: flat faces near a needle's line of sources err more
  // than the ball's (a line of monopoles, test_kirchhoff.cpp: 0.41 % at 4 cells, 0.56 % at 3).
  for (int a = 0; a < 3; ++a) shape.half_box_m[a] = half[a] + 4 * dx;
  return shape;
}

double kirchhoff_terms(const PanSpec& spec, const PanBody& body) {
  const auto& grid = (body.shape.octants == 8 ? spec.solve_full : spec.solve).problem.grid;
  return static_cast<double>(kernels::fdtd::staircase_surface(grid, kirchhoff_shape(spec, body)).size()) *
         (grid.octant ? 8 : 1);
}

model::PanProxy PanBody::entry() const {
  model::PanProxy e;
  e.b_m = b_m;
  e.c_m = c_m;
  e.mesh = shape;
  return e;
}

std::string PanBody::label() const {
  return mesh ? fmt::format("mesh '{}'", source) : fmt::format("(B, C) = ({:.4g}, {:.4g}) m", b_m, c_m);
}

namespace {

// A mesh entry: read, moved to its centre of mass, scaled to bounding radius a_m. `where` names it
// in messages ("config: key 'objects.meshes' entry 1 = 'x.obj'").
PanBody mesh_body(const std::string& path, const std::string& where, double a_m, bool all_octants) {
  auto bad = [&](const std::string& why) { return InputError(fmt::format("{}: {}", where, why)); };
  io::TriangleMesh mesh;
  try {
    mesh = io::read_obj(path);
  } catch (const InputError& e) {
    throw bad(e.what());
  }
  PanBody body;
  body.source = path;
  body.shape.key = io::mesh_hash(mesh);
  try {
    const kernels::fdtd::MeshBody given(mesh.vertices_m, mesh.triangles);  // its centre of mass and radius
    body.shape.centre_of_mass_m = given.centre_of_mass_offset_m();
    body.shape.scale = a_m / given.bounding_radius_m();
    for (auto& v : mesh.vertices_m)
      for (int a = 0; a < 3; ++a) v[a] = body.shape.scale * (v[a] - body.shape.centre_of_mass_m[a]);
    body.mesh = std::make_shared<const kernels::fdtd::MeshBody>(std::move(mesh.vertices_m), std::move(mesh.triangles));
  } catch (const std::invalid_argument& e) {
    throw bad(e.what());
  }
  // Without mirror symmetry in its own axes: the full domain, every octant its own directions.
  body.shape.octants = body.mesh->mirror_symmetric() && !all_octants ? 1 : 8;
  if (body.shape.octants == 8 && !all_octants) body.mirrored_axes = body.mesh->mirror_axes();
  body.shape.support_points_m = pan::support_points(body.mesh->vertices_m());
  return body;
}

std::vector<PanBody> bodies(const PanParams& in) {
  std::vector<PanBody> out;
  if (!in.objects_meshes.empty() || !in.objects_scene.empty()) {
    auto known = [&](const PanBody& b) {
      return std::find_if(out.begin(), out.end(), [&](const PanBody& o) { return o.shape.key == b.shape.key; });
    };
    for (std::size_t i = 0; i < in.objects_meshes.size(); ++i) {
      PanBody b = mesh_body(in.objects_meshes[i], fmt::format("config: key 'objects.meshes' entry {} = '{}'", i + 1,
                                                              in.objects_meshes[i]),
                            in.proxies_a_m, in.objects_all_octants);
      if (const auto it = known(b); it != out.end())
        throw InputError(fmt::format("config: key 'objects.meshes' entry {} = '{}': the same mesh as entry {} ('{}')",
                                     i + 1, in.objects_meshes[i], it - out.begin() + 1, it->source));
      out.push_back(std::move(b));
    }
    if (!in.objects_scene.empty()) {
      for (const auto& [path, where] : in.scene_meshes) {
        PanBody b = mesh_body(path, fmt::format("{}: mesh '{}'", where, path), in.proxies_a_m, in.objects_all_octants);
        if (known(b) == out.end()) out.push_back(std::move(b));
      }
      if (in.scene_meshes.empty() && out.empty())
        throw InputError(fmt::format("config: key 'objects.scene' = '{}': none of its {} objects is given by a mesh",
                                     in.objects_scene, in.scene_objects));
    }
    return out;
  }
  const auto list = proxy_list(in);
  for (std::size_t p = 0; p < list.size(); ++p) {
    const auto [b, c] = list[p];
    if (!(c <= b && b <= in.proxies_a_m))
      throw InputError(fmt::format("config: key 'proxies.list_m' proxy {} = [{}, {}]: needs C <= B <= A = {}", p + 1, b,
                                   c, in.proxies_a_m));
    PanBody body;
    body.b_m = b;
    body.c_m = c;
    out.push_back(std::move(body));
  }
  return out;
}

}  // namespace

PanSpec make_pan_spec(const PanParams& in) {
  PanSpec spec;
  spec.a_m = in.proxies_a_m;
  spec.bodies = bodies(in);
  spec.divisions = in.fit_divisions;
  spec.layout_levels = 0;
  while ((2 << spec.layout_levels) < spec.divisions) ++spec.layout_levels;
  if ((2 << spec.layout_levels) != spec.divisions)  // the layout is the 2-division octant split uniformly
    throw InputError(fmt::format("config: key 'fit.divisions' has {}: must be 2, 4, 8, 16, 32 or 64", spec.divisions));
  spec.direction_tolerance = in.fit_direction_tolerance;
  spec.direction_levels = in.fit_direction_levels;
  spec.max_directions = static_cast<std::size_t>(in.fit_max_directions);
  if (spec.direction_tolerance > 0 && spec.max_directions < static_cast<std::size_t>(pan::vertex_count(spec.divisions)))
    throw InputError(fmt::format("config: key 'fit.max_directions' has {}: fewer than the layout's {} directions "
                                 "(fit.divisions = {})", spec.max_directions, pan::vertex_count(spec.divisions), spec.divisions));
  spec.epsilon = in.fit_epsilon;
  const double c_m_s = in.medium_c_m_s, dt = in.time_dt_s, dx = in.grid_dx_m;
  if (in.fit_radii_m.empty()) throw InputError("config: key 'fit.radii_m' is empty: give at least one radius");
  for (double r : in.fit_radii_m) {
    const int k = static_cast<int>(std::lround(r / (c_m_s * dt)));
    if (!spec.shift_steps.empty() && k <= spec.shift_steps.back())
      throw InputError(fmt::format("config: key 'fit.radii_m' has {} after {}: the radii must ascend, at least one "
                                   "step c dt = {:.4g} m apart", r, spec.radii_m.back(), c_m_s * dt));
    spec.shift_steps.push_back(k);
    spec.radii_m.push_back(k * c_m_s * dt);
  }
  spec.solve = make_solve_spec(proxy_solve_params(in, spec));  // CFL, domain and listener checks
  spec.solve_full = spec.solve;
  if (std::any_of(spec.bodies.begin(), spec.bodies.end(), [](const PanBody& b) { return b.shape.octants == 8; })) {
    SolveParams full = proxy_solve_params(in, spec);
    full.grid_octant = false;
    spec.solve_full = make_solve_spec(full);
  }
  spec.solve.kirchhoff.radius_m = spec.solve_full.kirchhoff.radius_m = kirchhoff_radius_m(spec, dx);
  for (std::size_t i = 0; i < spec.radii_m.size(); ++i)  // every direction alike: the check along x
    if (auto why = surface_listener_problem(spec.solve, {spec.radii_m[i], 0.0, 0.0}))
      throw InputError(fmt::format("config: key 'fit.radii_m' has {}: {}", in.fit_radii_m[i], *why));
  spec.held_out_directions = in.check_held_out_directions;
  std::vector<double> held_out = in.check_held_out_radii_m;
  if (held_out.empty())
    for (std::size_t i = 0; i + 1 < spec.radii_m.size(); ++i) held_out.push_back(std::sqrt(spec.radii_m[i] * spec.radii_m[i + 1]));
  for (double r : held_out) {
    if (auto why = surface_listener_problem(spec.solve, {r, 0.0, 0.0}))
      throw InputError(fmt::format("config: key 'check.held_out_radii_m' has {}: {}", r, *why));
    spec.held_out_radii_m.push_back(std::round(r / (c_m_s * dt)) * c_m_s * dt);  // the raw series on PAN samples
  }
  spec.lead_steps = static_cast<int>(std::ceil(spec.a_m / (c_m_s * dt)));
  // The retarded window every radius hears: from lead_steps before the pulse to the end of the
  // outermost radius' record (the tail); nearer radii's later samples are dropped.
  const int k_max = spec.shift_steps.back() - spec.lead_steps;
  spec.length = static_cast<std::uint32_t>(pan::next_power_of_two(static_cast<std::size_t>(spec.solve.n_samples - k_max)));
  return spec;
}

model::PanBankHeader pan_header(const PanSpec& spec) {
  model::PanBankHeader h;
  const auto& p = spec.solve.problem;
  h.c_m_s = p.c_m_s;
  h.rho_kg_m3 = p.rho_kg_m3;
  h.h_s = p.h_s;
  h.dt_s = p.dt_s;
  h.t_first_s = -(spec.solve.i_time_zero + spec.lead_steps) * p.dt_s;
  h.epsilon = spec.epsilon;
  h.a_m = spec.a_m;
  h.length = spec.length;
  h.radii_m = spec.radii_m;
  h.divisions = 2;  // every set refines the 2-division octant: the layout's directions are coded hierarchically too
  h.max_levels = spec.layout_levels + spec.direction_levels;
  return h;
}

double mesh_width_cells(const PanBody& body, double dx_m) {
  if (!body.mesh) throw std::logic_error("mesh_width_cells: not a mesh entry");
  const auto props = kernels::mesh_mass_properties(body.mesh->vertices_m(), body.mesh->triangles());
  // Unit density: the fit's semi-axes do not depend on it.
  const kernels::ProxyFit fit = kernels::fit_proxy(props.inertia_per_density_m5, props.volume_m3, props.volume_m3);
  return 2 * fit.b_m / dx_m;
}

std::vector<PanTask> pan_tasks(const PanSpec& spec) {
  std::vector<PanTask> tasks;
  for (std::size_t p = 0; p < spec.bodies.size(); ++p)
    for (int field : spec.solve.fields)
      tasks.push_back({p, field, fmt::format("{}{:03}-f{}", spec.bodies[p].mesh ? 'o' : 'p', p, field)});
  return tasks;
}

namespace {

// The held-out draw's seed from what the entry is, not where it stands in the list: a proxy is
// checked at the same points in any bank that holds it. FNV-1a over (B, C) in micrometres, or
// over a mesh's key.
std::uint32_t held_out_seed(const PanBody& body) {
  std::uint32_t h = 2166136261u;
  auto mix = [&](const std::string& bytes) {
    for (const unsigned char c : bytes) h = (h ^ c) * 16777619u;
  };
  if (body.mesh) mix(body.shape.key);
  else mix(fmt::format("{},{}", std::lround(body.b_m * 1e6), std::lround(body.c_m * 1e6)));
  return h;
}

}  // namespace

std::vector<std::array<double, 3>> held_out_points(const PanSpec& spec, std::size_t proxy) {
  // std::mt19937's sequence is fixed by the standard; the distributions are not, hence Box-Muller
  // on its raw words: |three normals| is uniform over the octant's directions.
  std::mt19937 rng(held_out_seed(spec.bodies.at(proxy)));
  auto uniform = [&] { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; };
  auto normal = [&] { return std::sqrt(-2 * std::log(uniform())) * std::cos(2 * std::numbers::pi * uniform()); };
  // An entry of eight octants is checked over the sphere: the normals keep their signs.
  const bool sphere = spec.bodies.at(proxy).shape.octants == 8;
  auto component = [&] { const double x = normal(); return sphere ? x : std::abs(x); };
  std::vector<std::array<double, 3>> out;
  for (int i = 0; i < spec.held_out_directions; ++i) {
    std::array<double, 3> d{component(), component(), component()};
    const double n = std::hypot(d[0], d[1], d[2]);
    for (double r : spec.held_out_radii_m) out.push_back({r * d[0] / n, r * d[1] / n, r * d[2] / n});
  }
  return out;
}

double pan_series_per_task(const PanSpec& spec) {
  const double layout = pan::vertex_count(spec.divisions), radii = static_cast<double>(spec.radii_m.size());
  const double held_out = static_cast<double>(spec.held_out_directions) * static_cast<double>(spec.held_out_radii_m.size());
  if (spec.direction_tolerance == 0) return layout * (radii + 1) + held_out;
  return static_cast<double>(spec.max_directions) * (radii + 3) + held_out;
}

}  // namespace clatter::jobs
