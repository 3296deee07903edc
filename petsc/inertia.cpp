#include "petsc/inertia.hpp"

#include <cstdio>
#include <string>

#include "core/stage_log.hpp"
#include "petsc/error.hpp"
#include "petsc/subspace.hpp"

namespace clatter::petsc {
namespace {

// Owns the two PETSc objects of one factorisation, whatever throws.
struct Factorisation {
  Mat shifted = nullptr, factor = nullptr;
  ~Factorisation() {
    if (factor) MatDestroy(&factor);
    if (shifted) MatDestroy(&shifted);
  }
};

std::string format_interval(double lo, double hi) {
  char text[80];
  std::snprintf(text, sizeof text, "[%.17g, %.17g]", lo, hi);
  return text;
}

}  // namespace

namespace {

// K - sigma M factorised by MUMPS' LDL^T into f.
void factorise(const Matrix& K, const Matrix& M, double sigma, Factorisation& f, FactorStats& stats) {
  if (!(K.layout() == M.layout())) throw std::invalid_argument("K and M have different row layouts");
  check(MatDuplicate(K.get(), MAT_COPY_VALUES, &f.shifted), "MatDuplicate");
  const MatStructure structure =
      K.pattern_fingerprint() == M.pattern_fingerprint() ? SAME_NONZERO_PATTERN : DIFFERENT_NONZERO_PATTERN;
  check(MatAXPY(f.shifted, -sigma, M.get(), structure), "MatAXPY");
  check(MatGetFactor(f.shifted, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &f.factor), "MatGetFactor(mumps, cholesky)");
  // Without ICNTL(13)=1 MUMPS factorises the root front with ScaLAPACK and cannot count its pivots.
  check(MatMumpsSetIcntl(f.factor, 13, 1), "MatMumpsSetIcntl(13)");
  MatFactorInfo info;
  check(MatFactorInfoInitialize(&info), "MatFactorInfoInitialize");
  {
    Stage stage("factor symbolic");
    check(MatCholeskyFactorSymbolic(f.factor, f.shifted, nullptr, &info), "MatCholeskyFactorSymbolic");
    stats.symbolic_s = stage.elapsed_s();
  }
  {
    Stage stage("factor numeric");
    check(MatCholeskyFactorNumeric(f.factor, f.shifted, &info), "MatCholeskyFactorNumeric");
    stats.numeric_s = stage.elapsed_s();
  }
  check(MatMumpsGetInfog(f.factor, 21, &stats.memory_max_mb), "MatMumpsGetInfog(21)");
  check(MatMumpsGetInfog(f.factor, 22, &stats.memory_sum_mb), "MatMumpsGetInfog(22)");
}

}  // namespace

PetscInt eigenvalues_below(const Matrix& K, const Matrix& M, double sigma, FactorStats* stats) {
  Factorisation f;
  FactorStats local;
  factorise(K, M, sigma, f, local);
  // Zero and positive counts would need MUMPS' null-pivot detection (ICNTL(24)), which changes the
  // factorisation; the negative count is all Sylvester needs.
  PetscInt below = 0;
  check(MatGetInertia(f.factor, &below, nullptr, nullptr), "MatGetInertia");
  if (stats) *stats = local;
  return below;
}

std::vector<Vector> shift_invert(const Matrix& K, const Matrix& M, double sigma, std::span<const Vector> X) {
  Factorisation f;
  FactorStats stats;
  factorise(K, M, sigma, f, stats);
  Stage stage("factor solve");
  std::vector<Vector> out;
  for (const Vector& x : X) {
    Vector y(M.layout());
    check(MatSolve(f.factor, multiply(M, x).get(), y.get()), "MatSolve");
    out.push_back(std::move(y));
  }
  return out;
}

CountMismatch::CountMismatch(PetscInt found, PetscInt expected, double lambda_lo, double lambda_hi)
    : std::runtime_error("eigen-solve found " + std::to_string(found) + " eigenvalues in " +
                         format_interval(lambda_lo, lambda_hi) + " but the inertia of K - sigma M at its ends counts " +
                         std::to_string(expected)),
      found_(found),
      expected_(expected) {}

void check_count(PetscInt found, PetscInt expected, double lambda_lo, double lambda_hi) {
  if (found != expected) throw CountMismatch(found, expected, lambda_lo, lambda_hi);
}

}  // namespace clatter::petsc
