#pragma once
// The input contract of `clatter-bank pan`, without MPI: its config schema, the user's parameters
// parsed from it (PanParams), the validated PanSpec, the bank header and task list it implies. In
// clatter_specs (no MPI, no HDF5), so a fuzzer or a serial tool can check a PAN config exactly as
// clatter-bank does.
#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "banks/pan/solve_spec.hpp"
#include "model/pan_bank.hpp"

namespace clatter::jobs {

const io::Schema& pan_schema();
// `clatter-bank pan-object`: pan_schema's keys but the proxy grid's, and objects.meshes.
const io::Schema& pan_object_schema();

// One entry's body: a proxy ellipsoid (A, B, C), or a closed mesh (pan-object), normalized
// (model::PanMeshBody: moved to its centre of mass, scaled to bounding radius A).
struct PanBody {
  double b_m = 0, c_m = 0;
  std::shared_ptr<const kernels::fdtd::MeshBody> mesh;  // the normalized mesh, for a mesh entry
  model::PanMeshBody shape;                             // its key, scale, centre of mass, support points
  std::string source;                                   // the OBJ file as the config gives it
  // An entry of eight octants whose mesh is mirror-symmetric in one or two of its planes (bit a:
  // x_a -> -x_a; a plate in x and y, a mug across its handle): only the octants with those bits
  // clear are heard, the others are their mirror images with the field's parity (eqs. 16-21).
  // 0 for a proxy, a one-octant entry, and under objects.all_octants (every octant heard: the check).
  int mirrored_axes = 0;
  int heard_octants() const { return shape.octants >> std::popcount(static_cast<unsigned>(mirrored_axes)); }
  // An entry of the bank with this body and no fields (support_delay_samples reads it).
  model::PanProxy entry() const;
  // "(B, C) = (0.5, 0.12) m" or "mesh 'plate.obj'", for messages.
  std::string label() const;
};

struct PanSpec {
  // One entry's solve, body set per entry; its Kirchhoff surface hears the directions x radii and
  // the far fields (build_proxy, through run_solve's SurfaceHook).
  SolveSpec solve;
  // The full-domain solve (grid.octant = false) of a mesh entry without mirror symmetry, when the
  // spec has one; otherwise the same as `solve`.
  SolveSpec solve_full;
  std::vector<PanBody> bodies;  // the proxies (B, C), or pan-object's meshes
  double a_m = 0.5;
  std::vector<double> radii_m;         // ascending, whole numbers of steps: shift[i] * c * dt
  std::vector<int> shift_steps;
  // The retarded frame starts A/c before the pulse: no listener outside the bounding sphere hears
  // anything before t - R/c = -2h - A/c. Each series is shifted by shift_steps[i] - lead_steps.
  int lead_steps = 0;
  int divisions = 8;                   // the layout: octant triangulation, 8 -> 45 directions (the paper's)
  int layout_levels = 2;               // uniform splits of the 2-division root that make it (divisions = 2^(1 + levels))
  // Each field's directions: the layout refined where the far field between directions misses it
  // by more than direction_tolerance (0: the layout itself), at most direction_levels splits deep and
  // max_directions vertices (jobs::refine_directions).
  double direction_tolerance = 0.04;
  int direction_levels = 3;
  std::size_t max_directions = 1000;
  double epsilon = 0.01;
  std::uint32_t length = 0;            // wavelet length T
  // Each task's held-out check (held_out_points): directions per proxy x radii, whole steps of c dt.
  int held_out_directions = 8;
  std::vector<double> held_out_radii_m;
};

// The parameters of a PAN bank as the user gives them: one field per key of pan_schema(), named
// after it (section_key, with its unit); parse_pan_params has checked the schema's types and ranges.
struct PanParams {
  double medium_c_m_s = 0, medium_rho_kg_m3 = 0;
  double pulse_h_s = 0;
  double proxies_a_m = 0, proxies_grid_min_m = 0, proxies_grid_step_m = 0;
  std::vector<std::array<double, 2>> proxies_list_m;  // (B, C); when given, replaces the grid
  std::vector<std::string> objects_meshes;            // pan-object: the OBJ files (then no proxies)
  std::string objects_scene;                          // pan-object: a scene whose mesh objects are entries too
  // The scene's objects given by meshes, (OBJ path, where) each, and how many objects it has:
  // read_scene_meshes fills them (the scene reader is in the HDF5-linked io library; this one is not).
  std::vector<std::array<std::string, 2>> scene_meshes;
  std::size_t scene_objects = 0;
  bool objects_all_octants = false;                   // pan-object: every mesh in the full domain, eight octants
  double grid_dx_m = 0;
  int grid_pml_cells = 0;
  double time_dt_s = 0, time_tail_s = 0;
  std::vector<double> solve_fields;
  std::vector<double> fit_radii_m;
  int fit_divisions = 0;
  double fit_direction_tolerance = 0;
  int fit_direction_levels = 0;
  int fit_max_directions = 0;
  double fit_epsilon = 0;
  int check_held_out_directions = 0;
  std::vector<double> check_held_out_radii_m;
  int solver_cut_cell_samples = 0;
  std::string solver_scheme = "me4";
  double solver_max_dispersion_error = 0.02;
};

PanParams parse_pan_params(const io::Config& config);
// The same for pan_object_schema(): objects.meshes, the proxy grid's keys absent. The scene of
// objects.scene is read by read_scene_meshes (banks/pan/pan_job.hpp) before make_pan_spec.
PanParams parse_pan_object_params(const io::Config& config);

// Throws InputError for any invalid combination (the solve's checks included: make_solve_spec).
PanSpec make_pan_spec(const PanParams& params);
// make_pan_spec(parse_pan_params(config)).
PanSpec make_pan_spec(const io::Config& config);

model::PanBankHeader pan_header(const PanSpec& spec);

// The Kirchhoff surface of a body's solve: the spec's ball (the bounding sphere A + 3 cells) cut by
// the body's box + 4 cells (the ellipsoid's semi-axes, a mesh's extent about its centre of mass).
// Both hold the body with the faces' clearance, so their intersection does; a needle or a plate
// has far fewer faces, and hearing costs per face (docs/pan.md "Cost").
kernels::fdtd::SurfaceShape kirchhoff_shape(const PanSpec& spec, const PanBody& body);
// The terms a series heard through that surface sums per sample: its faces times their mirror
// images (8 in octant mode, 1 in the full domain of an entry of eight octants). The cost model
// of hearing (pan_plan.cpp).
double kirchhoff_terms(const PanSpec& spec, const PanBody& body);

// A mesh entry's planform width in cells: twice the middle semi-axis of its equivalent ellipsoid
// (kernels::fit_proxy of the normalized mesh, the proxy the synthesizer would give it) over
// grid.dx_m. A sharp-edged thin body's low-frequency radiation (its added mass, the first moment
// of its translation's far field) converges at first order, short by about 1.5 / width for a
// fracture piece of a plate (3.4 cells 42 %, 10.3 cells 16 %, 21 cells 7 %) and 1.1 / width for a
// flat box; a thin ellipsoid's, with no edge, is within 3 % at 6 cells (docs/pan.md "Proxy
// validation"). pan-object warns below kMinMeshWidthCells.
double mesh_width_cells(const PanBody& body, double dx_m);
inline constexpr double kMinMeshWidthCells = 15;

// The sweep (sweep/sweep.hpp): one task per entry and solved field, named "pNNN-fK" (a mesh
// entry: "oNNN-fK").
struct PanTask {
  std::size_t proxy = 0;
  int field = 1;
  std::string name;
};
std::vector<PanTask> pan_tasks(const PanSpec& spec);
// The points of proxy `proxy`'s held-out check, the same for its every field (so their energies
// compare): spec.held_out_directions directions uniform over the octant, with probability one
// inside the triangles of every direction set, from a generator seeded by the proxy's index (the
// same points on every machine), times each of spec.held_out_radii_m.
std::vector<std::array<double, 3>> held_out_points(const PanSpec& spec, std::size_t proxy);
// Series a task hears through the Kirchhoff surface, at most: directions x (radii + the far field),
// and with refinement the far fields at split points that did not become directions (about two per
// direction, measured: docs/pan.md), and the held-out check's points. With refinement the direction
// count is max_directions, a bound.
double pan_series_per_task(const PanSpec& spec);

}  // namespace clatter::jobs
