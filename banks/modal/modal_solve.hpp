#pragma once
// The eigen-solve of one ellipsoid's FEM model on its task group: the first elastic mode by one
// shift-and-invert solve, then every mode in [f_1, f_max] by SLEPc spectrum slicing (count-checked by
// inertia, rigid motions deflated) and on by the mesh's error margin, whole clusters kept, the basis rule of
// kernels/modal/mode_basis.hpp applied. Collective on the model's communicator.
#include <vector>

#include "banks/modal/modal_fem.hpp"
#include "model/modal_bank.hpp"
#include "petsc/eigen.hpp"

namespace clatter::jobs {

// Both solves take the bank header's settings (model::ModalBankHeader::solve) as they are.

// The lowest eigenvalue above the 6 rigid motions [rad^2/s^2]: one shift-and-invert Krylov-Schur
// solve at -guess/100 with the rigid motions deflated (petsc::lowest_eigenpairs), one
// factorisation. `guess` may be on either side, best within 100x. Of `settings` only tolerance
// and max_iterations are read. Throws TaskFailure when the solve fails or finds a near-zero
// eigenvalue besides the rigid motions (a spurious mode). Bit-reproducible on one rank.
double first_elastic_lambda(const FemModel& model, double guess, const model::ModalSolveSettings& settings);

// How fine a mesh is, for its frequency error: the edge length asked of the mesher from the shear
// wavelength at f_max (before the thickness cap, which only refines), and the shear speed.
struct MeshResolution {
  double edge_length_m = 0;
  double shear_speed_m_s = 0;
};

// The constant C of the error model e(f) = C (h f / c_s)^4 of 10-node tetrahedra (eigenvalue error
// O(h^4) for quadratic elements, hence the frequency's): the largest relative error up to f_max of
// the bank's glass sphere against Lamb's exact frequencies, over (h f_max / c_s)^4, measured 0.91 -
// 1.26 for f_max = 2 - 4 f_1 at 2.5 - 4 elements per wavelength, rising with f_max as the band's
// top modes turn into surface (Rayleigh) waves, 0.91 c_s at nu = 0.2, whose (c_s / c_R)^4 = 1.47
// bounds the rise near 1.4; 1.6 covers it (docs/modal.md "The band and what it guarantees";
// tests/mpi/test_modal_entry.cpp ModalEntrySlow.MeshErrorModelBoundsLamb measures it).
inline constexpr double kMeshErrorConstant = 1.6;

// The bound on the relative frequency error (FEM above exact) at `frequency_hz` on `mesh`; 0 for h = 0.
double mesh_frequency_error(const MeshResolution& mesh, double frequency_hz);

struct ModeSet {
  std::vector<double> lambdas;                 // ascending [rad^2/s^2]
  std::vector<petsc::Vector> vectors;          // M-normalized, basis rule applied
  std::vector<double> relative_residuals;
  std::vector<int> cluster;                    // cluster index per mode (neighbours within the cluster gap)
  model::ModalSolveRecord record;
  model::ModalBand band;
  petsc::SolveStats stats;
  int degenerate_groups = 0;
};

// Every mode from the first elastic one up to f_max (1 + e), f_max = f_max_multiple f_1, e =
// mesh_frequency_error(mesh, f_max), and the rest of the cluster that straddles it (so every mode
// whose exact frequency is at most f_max, and its whole multiplet). `lambda1_estimate`: from a
// coarser mesh (within a few %). A default `mesh` (h = 0) has no margin: the band ends at f_max
// (modal-samples' coarse solves, which want frequency ratios, not completeness).
// TaskFailure when the inertia count disagrees, the rigid motions are not exactly 6, or a residual
// exceeds the limit.
ModeSet solve_modes(const FemModel& model, const std::vector<petsc::Vector>& reference, double lambda1_estimate,
                    const model::ModalSolveSettings& settings, const MeshResolution& mesh = {});

}  // namespace clatter::jobs
