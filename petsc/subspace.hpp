#pragma once
// Small dense products with a few distributed vectors (Rayleigh-Ritz in a cluster of modes,
// projections onto reference fields): the m x n numbers are reduced over the layout's ranks, so
// every rank holds the same result. Collective on the vectors' communicator.
#include <cstddef>
#include <span>
#include <vector>

#include "petsc/matrix.hpp"
#include "petsc/vector.hpp"

namespace clatter::petsc {

// A x.
Vector multiply(const Matrix& A, const Vector& x);
// u_i . v_j as a row-major |U| x |V| array.
std::vector<double> inner_products(std::span<const Vector> U, std::span<const Vector> V);
// w_k = sum_i T(i, k) u_i for k < cols, T row-major |U| x cols.
std::vector<Vector> combine(std::span<const Vector> U, std::span<const double> T, std::size_t cols);

}  // namespace clatter::petsc

namespace clatter::petsc {
// ||k - lambda m||_2 / ||k||_2, for k = K u and m = M u: the relative residual of (lambda, u).
double relative_residual(const Vector& k, const Vector& m, double lambda);
}  // namespace clatter::petsc
