#pragma once
// The eigen-solve of one ellipsoid's FEM model on its task group: the first elastic mode by
// inertia bracketing, then every mode in [f_1, f_max] by SLEPc spectrum slicing (count-checked by
// inertia, rigid motions deflated), whole multiplets kept, the basis rule of
// kernels/modal/mode_basis.hpp applied. Collective on the model's communicator.
#include <vector>

#include "banks/modal/modal_fem.hpp"
#include "model/modal_bank.hpp"
#include "petsc/eigen.hpp"

namespace clatter::jobs {

// Both solves take the bank header's settings (model::ModalBankHeader::solve) as they are.

// The lowest eigenvalue above the 6 rigid motions [rad^2/s^2]. `guess` may be on either side.
// Of `settings` only the slicing's (tolerance, max_iterations, nev_per_shift) are read.
// Throws TaskFailure when the inertia never shows exactly 6 motions below a shift.
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
