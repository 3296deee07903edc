#pragma once
// `clatter-bank pan`: the PAN proxy bank (Chadwick et al. 2012, sections 4-5). For each proxy
// ellipsoid (A, B, C): octant FDTD solves of the 6 rigid-body fields heard through a Kirchhoff
// surface at each field's directions (the paper's 45, refined where the far field needs more:
// refine_directions) x M radii and at infinity (the far field), the radial model's wavelet
// coefficients of each direction (kernels/pan/fit.hpp), and the compressed bank file (io/pan_bank.hpp).
#include <mpi.h>

#include <array>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/config.hpp"
#include "io/pan_bank.hpp"
#include "kernels/fdtd/kirchhoff.hpp"
#include "kernels/pan/direction_mesh.hpp"
#include "banks/pan/pan_spec.hpp"
#include "banks/pan/solve_job.hpp"
#include "sweep/sweep.hpp"
#include "model/pan_bank.hpp"

namespace clatter::jobs {

// Solves one proxy (all ranks) and fits it (rank 0). `extra_listeners_m` are recorded too and
// returned raw per field (validation); on other ranks the result is empty.
struct ProxyResult {
  model::PanProxy proxy;
  std::vector<std::vector<float>> extra_series;  // per field: [extra listener][sample]
};
ProxyResult build_proxy(MPI_Comm comm, const PanSpec& spec, std::size_t proxy,
                        const std::vector<std::array<double, 3>>& extra_listeners_m, double progress_interval_s);

// The far field of proxy `proxy` in unit direction d on a bank's coefficient frame (spec.length
// samples), aligned by the direction's exact support distance like every stored direction.
std::vector<double> aligned_far_field(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                      const std::array<double, 3>& d);
// The same for several directions, heard in one pass over the surface per few of them.
std::vector<std::vector<double>> aligned_far_fields(const PanSpec& spec, std::size_t proxy,
                                                    const kernels::fdtd::SurfaceField& surface,
                                                    const std::vector<std::array<double, 3>>& d);

// What a bank stores for direction d: the aligned far field over the field's symmetry zeros (q,
// kernels/pan/directions.hpp symmetry_zeros), heard off the planes where they vanish.
// An entry of eight octants stores every octant's field as it is: `octant` mirrors d (a direction
// of the positive octant) into it, and nothing is divided.
std::vector<double> stored_far_field(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                     const std::array<double, 3>& d, int octant = 0);
std::vector<std::vector<double>> stored_far_fields(const PanSpec& spec, std::size_t proxy,
                                                   const kernels::fdtd::SurfaceField& surface,
                                                   const std::vector<std::array<double, 3>>& d, int octant = 0);
// Where a stored direction d (of the positive octant) is heard: off the field's planes
// (kernels/pan/directions.hpp off_planes), or for an entry of eight octants d in `octant`.
std::array<double, 3> heard_direction(const PanSpec& spec, std::size_t proxy, int field, int octant,
                                      const std::array<double, 3>& d);

// A field's strength over the layout's directions: its strongest far field (L2 over time) and
// their energy (the sum of squares, the layout's directions spanning about equal solid angles).
struct FarFieldStrength {
  double strongest_l2 = 0;
  double energy = 0;
};
FarFieldStrength layout_strength(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                 int octant = 0);

// A field's adaptive direction set (the bank's, with fit.direction_tolerance): the layout of
// spec.divisions split where quadratic interpolation of the far field misses it at a split point
// by more than `tolerance` (relative L2), the far field as stored (stored_far_field: over the
// symmetry zeros). Directions weaker than far_field_floor (1.5 % of the strongest stored far field
// among the layout's vertices, or of the strongest p over Z_f there) are judged against it. A field that does
// not radiate, below kRadiatedEnergy of `yardstick_energy` (the proxy's strongest field's, known from
// another solve; build_proxy: field 3's, a rotation field's taken per unit surface acceleration),
// is numerical noise and stays at the layout.
struct DirectionRefinement {
  kernels::pan::DirectionMesh mesh;
  int splits = 0;
  // The far fields heard through the surface (vertices and split points), aligned, by lattice key.
  std::unordered_map<std::int64_t, std::vector<double>> far_fields;
  FarFieldStrength strength;  // this field's layout_strength
  // False below kRadiatedEnergy of the yardstick: left at the layout, and fitted as it is.
  bool radiated = true;
  // True below kSilentEnergy: what the surface hears is the solve's noise (the sphere's rotations,
  // a needle's turn about its own axis), stored with no coefficients; it sounds as silence.
  bool silent = false;
};
// Issue 32 excludes fields below 1 % of the strongest field's energy at the listeners. The
// refinement decides before it knows the other fields, from the far field over the layout and
// against field 3, which is not always the strongest: a quarter of that share leaves a margin for
// both (measured, docs/pan.md "Adaptive directions").
inline constexpr double kRadiatedEnergy = 0.0025;
// A field whose far field over the layout carries less than this share of the yardstick's energy
// (0.3 % of its amplitude, 50 dB down) is the solve's noise. A weak field that is real, such as a
// thin plate's translation along its own plane, lies between this and kRadiatedEnergy: stored.
inline constexpr double kSilentEnergy = 1e-5;
DirectionRefinement refine_directions(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface,
                                      double tolerance, int max_levels, std::size_t max_vertices,
                                      double yardstick_energy = 0, int octant = 0);
// The miss measure of refine_directions: |interpolated - truth| / max(|truth|, floor), L2 over time.
double far_field_miss(const std::vector<double>& interpolated, const std::vector<double>& truth, double floor);
// 1.5 % of the strongest far field (L2) among the layout's directions, 2e-4 of its energy.
double far_field_floor(const PanSpec& spec, std::size_t proxy, const kernels::fdtd::SurfaceField& surface);

// The held-out check (tests, each task's check): the relative L2 of the bank's field at
// x against a raw series heard there in the same solve (build_proxy's extra listeners, the solve's
// samples), the bank read at the raw sample times by cubic Lagrange interpolation.
double held_out_error(const PanSpec& spec, const model::PanBankHeader& header, const model::PanProxy& proxy, int field,
                      const std::array<double, 3>& x_m, const float* raw,
                      kernels::pan::Interpolation interpolation = kernels::pan::Interpolation::quadratic);

// The held-out check of one field (merge_pan_results; the raw series come from its task): field
// `field` of `built` as the bank stores it (io::stored_field) against the raw series heard at
// `points` (build_proxy's extra listeners, [point][sample]).
model::PanHeldOut check_held_out(const PanSpec& spec, const model::PanBankHeader& header, const model::PanProxy& built,
                                 int field, const std::vector<std::array<double, 3>>& points, const std::vector<float>& raw);

// pan-object's objects.scene: the scene's objects given by meshes into params.scene_meshes (the
// scene reader is io's; InputError names the scene's file and value).
void read_scene_meshes(PanParams& params);

// Solves and fits one task on `group`, hearing its raw field at held_out_points too; the writer of its result on the group's rank 0.
TaskWriter run_pan_task(MPI_Comm group, const PanSpec& spec, const PanTask& task, double progress_interval_s);
// The bank from a results folder: every task found done, the others listed as failed or missing;
// each field held-out checked (check_held_out).
model::PanBank merge_pan_results(const PanSpec& spec, const std::string& results_dir, const std::string& config_toml);

}  // namespace clatter::jobs
