#include "kernels/modal/mode_basis.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace clatter::kernels::modal {
namespace {

// The 20 exponents (p, q, r) with p + q + r <= 3, by degree, then lexicographically descending.
const std::array<std::array<int, 3>, 20>& monomials() {
  static const auto table = [] {
    std::array<std::array<int, 3>, 20> t{};
    int k = 0;
    for (int degree = 0; degree <= 3; ++degree)
      for (int p = degree; p >= 0; --p)
        for (int q = degree - p; q >= 0; --q) t[static_cast<std::size_t>(k++)] = {p, q, degree - p - q};
    return t;
  }();
  return table;
}

// U <- U Q for one group of (numerically) equal Ritz values, Q from the pivoted QR of its C rows.
double fix_group(const Eigen::MatrixXd& c_rows, Eigen::Ref<Eigen::MatrixXd> rotation) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(c_rows);
  Eigen::MatrixXd q = qr.householderQ();
  const Eigen::MatrixXd r = qr.matrixQR().triangularView<Eigen::Upper>();
  const auto m = c_rows.rows();
  double smallest = 1;
  for (Eigen::Index i = 0; i < m; ++i) {
    if (r(i, i) < 0) q.col(i) *= -1;
    if (std::abs(r(0, 0)) > 0) smallest = std::min(smallest, std::abs(r(i, i)) / std::abs(r(0, 0)));
  }
  rotation = (rotation * q).eval();
  return smallest;
}

}  // namespace

std::vector<std::pair<int, int>> clusters_by_gap(std::span<const double> v, double gap) {
  std::vector<std::pair<int, int>> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const int at = static_cast<int>(i);
    if (out.empty() || std::abs(v[i] - v[i - 1]) > gap * std::abs(v[i])) out.emplace_back(at, at);
    out.back().second = at + 1;
  }
  return out;
}

Eigen::Vector3d reference_field(int j, const Eigen::Vector3d& x) {
  const auto& e = monomials()[static_cast<std::size_t>(j / 3)];
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  v(j % 3) = std::pow(x(0), e[0]) * std::pow(x(1), e[1]) * std::pow(x(2), e[2]);
  return v;
}

ClusterBasis cluster_basis(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                           double degenerate_gap) {
  const auto m = A.rows();
  if (A.cols() != m || B.rows() != m || B.cols() != m || C.rows() != m)
    throw std::invalid_argument("cluster_basis: A, B and C must have the cluster's size");
  ClusterBasis out;
  // Symmetrized: the projections are symmetric only to rounding.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(0.5 * (A + A.transpose()),
                                                                       0.5 * (B + B.transpose()));
  if (ritz.info() != Eigen::Success) throw std::runtime_error("cluster_basis: the projected pencil is not definite");
  out.rotation = ritz.eigenvectors();  // Y^T B Y = I
  out.lambdas.assign(ritz.eigenvalues().data(), ritz.eigenvalues().data() + m);
  const Eigen::MatrixXd projected = out.rotation.transpose() * C;
  for (const auto& [begin, end] : clusters_by_gap(out.lambdas, degenerate_gap)) {
    const int size = end - begin;
    const double margin = fix_group(projected.middleRows(begin, size), out.rotation.middleCols(begin, size));
    if (size > 1) {
      ++out.degenerate_groups;
      out.rank_margin = std::min(out.rank_margin, margin);
    }
  }
  return out;
}

}  // namespace clatter::kernels::modal
