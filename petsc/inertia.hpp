#pragma once
#include <petscsys.h>

#include <span>
#include <stdexcept>
#include <vector>

#include "petsc/matrix.hpp"
#include "petsc/vector.hpp"

namespace clatter::petsc {

// What one MUMPS factorisation cost (MUMPS' INFOG(21), INFOG(22): memory effectively used, in MB).
struct FactorStats {
  double symbolic_s = 0, numeric_s = 0;
  PetscInt memory_max_mb = 0, memory_sum_mb = 0;  // largest rank, sum over ranks
};

// Sylvester's law of inertia for K x = lambda M x with M positive definite: the number of
// negative pivots of an LDL^T factorisation of K - sigma M is the number of eigenvalues below
// sigma. Collective on K's communicator: factorises with MUMPS (ICNTL(13)=1 so the count is exact
// in parallel too); stages "factor symbolic" and "factor numeric". Sigma should not be an
// eigenvalue (a singular K - sigma M counts its zero pivot either way).
PetscInt eigenvalues_below(const Matrix& K, const Matrix& M, double sigma, FactorStats* stats = nullptr);

// Inverse iteration's step: (K - sigma M)^-1 M x for each x, from one MUMPS LDL^T factorisation of
// K - sigma M (sigma not an eigenvalue; the closer to the wanted ones, the more one step removes of
// the others). Collective on K's communicator; stages as above and "factor solve".
std::vector<Vector> shift_invert(const Matrix& K, const Matrix& M, double sigma, std::span<const Vector> X);

// The eigen-solve found a different number of eigenvalues in [lambda_lo, lambda_hi] than the
// inertia counts: an eigenvalue was lost or duplicated.
class CountMismatch : public std::runtime_error {
 public:
  CountMismatch(PetscInt found, PetscInt expected, double lambda_lo, double lambda_hi);
  PetscInt found() const { return found_; }
  PetscInt expected() const { return expected_; }

 private:
  PetscInt found_, expected_;
};

// Throws CountMismatch unless found == expected.
void check_count(PetscInt found, PetscInt expected, double lambda_lo, double lambda_hi);

}  // namespace clatter::petsc
