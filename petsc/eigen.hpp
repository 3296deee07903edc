#pragma once
#include <petscsys.h>

#include <span>
#include <string>
#include <vector>

#include "petsc/inertia.hpp"
#include "petsc/matrix.hpp"
#include "petsc/options.hpp"
#include "petsc/vector.hpp"

namespace clatter::petsc {

// All eigenpairs of K x = lambda M x (K symmetric, M symmetric positive definite) with lambda in
// [lambda_lo, lambda_hi]: SLEPc's Krylov-Schur with spectrum slicing, shift-and-invert, each shift
// factorised by MUMPS' parallel LDL^T. Neither end may be an eigenvalue (pick ends in gaps).
struct SliceSettings {
  double lambda_lo = 0, lambda_hi = 0;
  double tolerance = 1e-12;      // SLEPc's relative convergence tolerance (-eps_tol)
  PetscInt max_iterations = 0;   // restarts per shift (-eps_max_it); 0: SLEPc's default
  PetscInt nev_per_shift = 0;    // eigenpairs sought around each shift (-eps_krylovschur_nev); 0: default
};

// The options database a solve on `settings` gives SLEPc, and through it the ST, KSP, PC and the
// MUMPS factor (all under the st_ prefix). `same_pattern`: K and M share their nonzero pattern, so
// K - sigma M is formed in place.
Options slice_options(const SliceSettings& settings, bool same_pattern);

struct SolveStats {
  double setup_s = 0, solve_s = 0;           // EPSSetUp (first factorisations), EPSSolve
  PetscInt shifts = 0;                       // shifts SLEPc factorised at, ends included
  long long symbolic_factorisations = 0, numeric_factorisations = 0;  // inside the solve (PETSc's log)
  double symbolic_s = 0, numeric_s = 0;
  FactorStats check_factor;                  // the count check's factorisation at lambda_hi
  double memory_max_mb = 0;                  // resident memory after the solve, largest rank
};

struct EigenSolution {
  std::vector<double> lambdas;                // ascending
  std::vector<Vector> vectors;                // x^T M x = 1; the largest |entry| (first of equals) > 0
  std::vector<double> relative_residuals;     // ||K x - lambda M x||_2 / ||K x||_2, computed here
  PetscInt below_lo = 0, below_hi = 0;        // eigenvalues below each end, by inertia
  PetscInt deflated_in_interval = 0;          // deflation vectors whose eigenvalue is in the interval
  std::string options;                        // Options::text() of the solve: its provenance
  SolveStats stats;
};

// Collective on K's communicator (a task group's, never PETSC_COMM_WORLD implicitly). `deflation`:
// vectors spanning eigenvectors to leave out (the rigid-body motions of a free body, K x = 0; then
// put lambda_lo below 0, K itself being singular). SLEPc 3.18 cannot slice with a deflation space
// (EPSSetDeflationSpace), so the interval is solved in full and the pairs in the space are removed;
// each deflation vector counts at its Rayleigh quotient, and the count check expects below_hi -
// below_lo minus those inside the interval. Throws CountMismatch when another number was found,
// Error on a PETSc failure, std::invalid_argument on bad settings. Stages: "eigensolve" with
// "setup", "solve" (PETSc's "factor symbolic", "factor numeric" inside), "count check".
EigenSolution solve_interval(const Matrix& K, const Matrix& M, const SliceSettings& settings,
                             std::span<const Vector> deflation = {});

// The `count` lowest eigenpairs of K x = lambda M x above `shift` (below every wanted eigenvalue; a
// free body's K is singular, so put it below 0): SLEPc's Krylov-Schur on the shift-inverted pencil,
// one MUMPS LDL^T factorisation of K - shift M, the `deflation` vectors (the rigid motions) kept
// out of the Krylov space by EPSSetDeflationSpace, which SLEPc 3.18 allows without slicing. The
// closer the shift to the first eigenvalue (relative to the gap to the next), the fewer the
// iterations. No inertia check: a start vector without a component along the lowest eigenvector
// would miss it, which a random start does not in practice; where completeness matters, slice.
struct LowestSettings {
  double shift = 0;
  PetscInt count = 1;
  double tolerance = 1e-12;     // -eps_tol
  PetscInt max_iterations = 0;  // restarts (-eps_max_it); 0: SLEPc's default
};

// Collective on K's communicator. lambdas ascending, vectors as solve_interval's (M-normalised,
// sign fixed), relative residuals; below_lo, below_hi and the count check are not computed.
// Throws Error on a PETSc failure, std::runtime_error when fewer than `count` pairs converged.
EigenSolution lowest_eigenpairs(const Matrix& K, const Matrix& M, const LowestSettings& settings,
                                std::span<const Vector> deflation = {});

}  // namespace clatter::petsc
