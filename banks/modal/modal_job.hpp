#pragma once
// One entry of the modal bank (003 §5): the ellipsoid meshed twice (a coarse pre-solve estimates
// f_1, which sets h from the shear wavelength at f_max and the sliced interval), K and M assembled
// on the task group, every mode in [f_1, f_max] solved and fixed by the basis rule, the shapes
// gathered on the surface.
#include <mpi.h>

#include <cmath>
#include <numbers>
#include <string>

#include "banks/modal/modal_fem.hpp"
#include "banks/modal/modal_solve.hpp"
#include "banks/modal/modal_spec.hpp"
#include "kernels/modal/multiplets.hpp"
#include "sweep/sweep.hpp"
#include "model/modal_bank.hpp"

namespace clatter::jobs {

// Collective on `group`; the full entry on the group's rank 0, an empty one elsewhere. Throws
// TaskFailure (mesh quality, count check, residual) or Interrupted, alike on every rank.
model::ModalEntry build_modal_entry(MPI_Comm group, const ModalSpec& spec, std::size_t entry);

// The sweep's task: build_modal_entry and, on the group leader, the writer of its task file.
TaskWriter run_modal_task(MPI_Comm group, const ModalSpec& spec, const ModalTask& task);

// The bank from a results folder: every task found done, the others listed as failed or missing.
// The header's ranks_per_task is the entries' common group size (0 when a resume changed it).
model::ModalBank merge_modal_results(const ModalSpec& spec, const std::string& results_dir,
                                     const std::string& config_toml);

// The ellipsoid's mesh at edge length h_m, at most 2 a / elements_through_thickness (a the smallest
// semi-axis), or, when it breaks the quality bounds, at 0.7 and then 0.5 times h_m, that cap and
// the surface spacing per curvature radius (a finer surface resolves the curvature that folded);
// throws a MeshError with every attempt's reason. Deterministic, so every rank of a group gets
// the same mesh.
// Flat entries (a < header.layered_below_ratio x b) are meshed in layers instead
// (kernels::fem::mesh_layered_ellipsoid): header.layers (coarse_layers) through the thickness, and
// in the plane the smaller of h_m and layered_edge_length_m for an entry, h_m itself for the
// pre-solve (its first mode, a bending wave as long as the body, needs no more).
enum class MeshFor { entry, estimate };
kernels::fem::EllipsoidMesh mesh_entry(const ModalSpec& spec, const std::array<double, 3>& axes, double h_m,
                                       double elements_through_thickness, MeshFor purpose = MeshFor::entry);
bool layered_entry(const model::ModalBankHeader& header, const std::array<double, 3>& axes);

// The in-plane h of a layered entry: the bending wavelength, at the frequency h_m resolves (h_m
// elements_per_wavelength = c_s / f), of a plate 2a thick, over kBendingOverShear x
// elements_per_wavelength; at most h_m. Bending waves need more elements than shear waves for the
// same error: of a 0.03:1:1 entry's first 10 frequencies, the worst is 8.7 % high at 3 per bending
// wavelength, 0.64 % at 8 and 0.4 % at 10 (docs/modal.md "Thin entries", the sequence).
inline constexpr double kBendingOverShear = 10.0 / 3;
double layered_edge_length_m(const model::ModalBankHeader& header, const std::array<double, 3>& axes, double h_m);

// The pre-solve that estimates f_1 (stage `estimate`, docs/modal.md): the ellipsoid meshed at
// header.coarse_edge_m (mesh_entry; a failure is the task's TaskFailure), K and M assembled on
// `comm`, and the lowest elastic eigenvalue bracketed from the guess of a sphere of radius c
// (omega c / c_s ~ 2.5) with the header's solve settings. The one definition that the job, `plan`
// and `modal-samples` share, so their f_1 agree to the bit. Collective on `comm`.
// The frequency [Hz] of an eigenvalue omega^2 [rad^2/s^2].
inline double frequency_hz(double lambda) { return std::sqrt(lambda) / (2 * std::numbers::pi); }

struct FirstModeEstimate {
  kernels::fem::EllipsoidMesh mesh;  // the coarse mesh
  FemModel model;                    // its K and M
  double lambda1 = 0;                // omega_1^2 [rad^2/s^2]
  double f1_hz() const { return frequency_hz(lambda1); }
};
FirstModeEstimate estimate_first_mode(MPI_Comm comm, const ModalSpec& spec, const std::array<double, 3>& axes);

// What the modal and object kinds share after the solve.
model::ModalMeshStats mesh_stats(const kernels::fem::MeshQuality& quality);
// On the group's rank 0, into `entry`: the surface nodes of `boundary` (in ascending mesh order)
// and its faces renumbered onto them, every mode's frequency, damping in `material`, cluster and
// residual, and its shape at the surface nodes; the band; the multiplets that `symmetry` makes of
// the clusters (kernels/modal/multiplets.hpp). Collective on `group` (the vectors are gathered).
void store_modes(MPI_Comm group, const ModeSet& modes, const kernels::fem::Tet10Mesh& mesh,
                 const std::vector<kernels::fem::BoundaryFace>& boundary, const model::Material& material,
                 const kernels::modal::EllipsoidSymmetry& symmetry, model::ModalEntry& entry);

// The band multiple k of an entry (model::ModalBand): from its normalized axes and the pre-solve's f_1.
double entry_band_multiple(const ModalSpec& spec, const std::array<double, 3>& axes, double f1_hz);

// The edge length that resolves the shear wavelength at f_max: c_s / f_max / elements_per_wavelength.
double modal_edge_length_m(const ModalSpec& spec, double f_max_hz);

}  // namespace clatter::jobs
