#pragma once
// The eigen-solve of one ellipsoid's FEM model on its task group: the first elastic mode by one
// shift-and-invert solve, then every mode in [f_1, f_max] by SLEPc spectrum slicing (count-checked by
// inertia, rigid motions deflated), whole multiplets kept, the basis rule of
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

struct ModeSet {
  std::vector<double> lambdas;                 // ascending [rad^2/s^2]
  std::vector<petsc::Vector> vectors;          // M-normalized, basis rule applied
  std::vector<double> relative_residuals;
  std::vector<int> cluster;                    // multiplet index per mode
  model::ModalSolveRecord record;
  petsc::SolveStats stats;
  int degenerate_groups = 0;
};

// Every mode from the first elastic one up to (f_max_multiple f_1)^2, and the rest of the
// multiplet that straddles it. `lambda1_estimate`: from a coarser mesh (within a few %).
// TaskFailure when the inertia count disagrees, the rigid motions are not exactly 6, or a residual
// exceeds the limit.
ModeSet solve_modes(const FemModel& model, const std::vector<petsc::Vector>& reference, double lambda1_estimate,
                    const model::ModalSolveSettings& settings);

}  // namespace clatter::jobs
