#include "petsc/subspace.hpp"

#include <stdexcept>

#include "petsc/error.hpp"

namespace clatter::petsc {
namespace {

std::vector<Vec> handles(std::span<const Vector> v) {
  std::vector<Vec> out;
  for (const Vector& x : v) out.push_back(x.get());
  return out;
}

}  // namespace

Vector multiply(const Matrix& A, const Vector& x) {
  Vector y(x.layout());
  check(MatMult(A.get(), x.get(), y.get()), "MatMult");
  return y;
}

std::vector<double> inner_products(std::span<const Vector> U, std::span<const Vector> V) {
  std::vector<double> out(U.size() * V.size());
  if (V.empty()) return out;
  const std::vector<Vec> v = handles(V);
  for (std::size_t i = 0; i < U.size(); ++i)
    check(VecMDot(U[i].get(), static_cast<PetscInt>(v.size()), v.data(), out.data() + i * V.size()), "VecMDot");
  return out;
}

std::vector<Vector> combine(std::span<const Vector> U, std::span<const double> T, std::size_t cols) {
  if (T.size() != U.size() * cols) throw std::invalid_argument("combine: T must hold |U| x cols values");
  std::vector<Vector> out;
  if (U.empty()) return out;
  std::vector<Vec> u = handles(U);  // VecMAXPY takes Vec*, though it only reads them
  std::vector<PetscScalar> column(U.size());
  for (std::size_t k = 0; k < cols; ++k) {
    for (std::size_t i = 0; i < U.size(); ++i) column[i] = T[i * cols + k];
    Vector w(U[0].layout());
    check(VecMAXPY(w.get(), static_cast<PetscInt>(u.size()), column.data(), u.data()), "VecMAXPY");
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace clatter::petsc

namespace clatter::petsc {
double relative_residual(const Vector& k, const Vector& m, double lambda) {
  Vector r(k.layout());
  check(VecWAXPY(r.get(), -lambda, m.get(), k.get()), "VecWAXPY");
  PetscReal rn = 0, kn = 0;
  check(VecNorm(r.get(), NORM_2, &rn), "VecNorm");
  check(VecNorm(k.get(), NORM_2, &kn), "VecNorm");
  return kn > 0 ? rn / kn : rn;
}
}  // namespace clatter::petsc
