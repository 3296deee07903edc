#pragma once
// The input contract of `clatter-bank solve`: its config schema, the user's parameters parsed from
// it (SolveParams), and the validated SolveSpec that every FDTD solve (a solve job, or one proxy of
// a PAN sweep) runs from. Parsing (config -> SolveParams) is apart from validation (SolveParams ->
// SolveSpec), so a PAN sweep builds its solve's parameters as a struct.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "kernels/fdtd/kirchhoff.hpp"
#include "kernels/fdtd/problem.hpp"

namespace clatter::jobs {

const io::Schema& solve_schema();

inline constexpr const char* kRawFormat = "clatter-fdtd-raw";
inline constexpr int kRawFormatVersion = 2;

// The parameters of a solve as the user gives them: one field per key of solve_schema(), named
// after it (section_key, with its unit). parse_solve_params has checked only the schema's types and
// ranges; the defaults are parse_solve_params(io::Config(solve_schema())).
struct SolveParams {
  double medium_c_m_s = 0, medium_rho_kg_m3 = 0;
  double pulse_h_s = 0;
  std::string object_kind;  // "ellipsoid", "mesh" or "monopole"
  double object_a_m = 0, object_b_m = 0, object_c_m = 0;
  std::string object_mesh;  // kind "mesh": the OBJ file
  double object_scale = 1;  // kind "mesh": factor on its coordinates
  double grid_dx_m = 0, grid_half_width_m = 0;
  int grid_pml_cells = 0;
  bool grid_octant = true;
  double time_dt_s = 0, time_duration_s = 0;
  std::vector<double> solve_fields;  // as given (make_solve_spec checks they are whole)
  std::vector<std::array<double, 3>> listeners_points_m;
  int solver_cut_cell_samples = 0;
  double solver_pml_reflection = 0;
  std::string solver_scheme = "me4";
  double solver_max_dispersion_error = 0.02;
  double kirchhoff_radius_m = 0;  // 0: no Kirchhoff surface
  std::vector<std::array<double, 3>> kirchhoff_far_directions;
};

SolveParams parse_solve_params(const io::Config& config);

// A validated solve: everything is checked here, before any stepping.
struct SolveSpec {
  kernels::fdtd::Problem problem;  // field set per solve
  std::vector<int> fields;         // 1..6, or {0} for the monopole
  std::vector<std::array<double, 3>> listeners_m;
  // The Kirchhoff surface (kernels/fdtd/kirchhoff.hpp; radius 0: none): its staircase ball (a PAN
  // task cuts it by the body's box), and what it gives: the far field R p in each of
  // far_directions, and the field at surface_listeners_m (points anywhere outside the surface,
  // beyond the grid's edge too).
  kernels::fdtd::SurfaceShape kirchhoff;
  std::vector<std::array<double, 3>> far_directions;
  std::vector<std::array<double, 3>> surface_listeners_m;
  int i_time_zero = 0;             // sample index of t = 0 (the centre of psi)
  int n_samples = 0;               // samples per series, t_k = (k - i_time_zero) dt
  // The resolution, as the error budget (docs/fdtd.md) sees it.
  double band_edge_hz = 0;         // psi's band edge (-40 dB)
  double farthest_m = 0;           // longest listener distance from the body's bounding sphere
  double predicted_error = 0;      // worst-direction dispersion error of psi over farthest_m
  double max_dispersion_error = 0; // the bound above which the solve warns
  // A body given as a mesh (problem.mesh set): its file, io::mesh_hash of the mesh as read, and
  // its scale; the centre-of-mass offset is problem.mesh->centre_of_mass_offset_m().
  std::string mesh_path, mesh_hash;
  double mesh_scale = 1;
};

// The Kirchhoff surface's rule for a point x (spec.kirchhoff.radius_m > 0): heard through the
// surface when beyond surface_outside_m (the faces reach radius + dx / sqrt 2, kernels/fdtd/kirchhoff.hpp;
// one cell more to spare); and refused when its sound would arrive after the record ends (it
// would be heard as silence). The reason, or nullopt where x can be heard.
double surface_outside_m(const SolveSpec& spec);
std::optional<std::string> surface_listener_problem(const SolveSpec& spec, const std::array<double, 3>& x);

// Throws InputError naming the key and value for any invalid combination.
SolveSpec make_solve_spec(const SolveParams& params);
// make_solve_spec(parse_solve_params(config)).
SolveSpec make_solve_spec(const io::Config& config);

}  // namespace clatter::jobs
