// The basis rule of the modal bank (kernels/modal/mode_basis.hpp): the rotated vectors do not
// depend on which basis of a degenerate subspace the solver returned, nor on the sign of a single
// mode; Rayleigh-Ritz recovers the eigenvectors of a split cluster from any basis of its span.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "kernels/modal/mode_basis.hpp"
#include "tests/reference/random_orthogonal.hpp"

namespace {
using namespace clatter::kernels::modal;

using clatter::reference::random_orthogonal;

// A model problem: K = diag(lambdas) in an orthonormal basis E of R^n (M = I), U = E[:, cluster] S
// for an arbitrary orthogonal S; G: fixed reference columns.
struct Model {
  Eigen::MatrixXd E, G, K;
};
Model model(const std::vector<double>& lambdas, int n) {
  Model m;
  m.E = random_orthogonal(n, 7);
  Eigen::VectorXd d = Eigen::VectorXd::Constant(n, 100.0);
  for (std::size_t i = 0; i < lambdas.size(); ++i) d(static_cast<Eigen::Index>(i)) = lambdas[i];
  m.K = m.E * d.asDiagonal() * m.E.transpose();
  std::mt19937 gen(11);
  std::normal_distribution<double> normal;
  m.G.resize(n, kReferenceFields);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < kReferenceFields; ++j) m.G(i, j) = normal(gen);
  return m;
}

Eigen::MatrixXd apply_rule(const Model& m, const Eigen::MatrixXd& U, double degenerate_gap) {
  const Eigen::MatrixXd A = U.transpose() * m.K * U, B = U.transpose() * U, C = U.transpose() * m.G;
  return U * cluster_basis(A, B, C, degenerate_gap).rotation;
}

TEST(ModeBasis, DegenerateSubspaceGetsTheSameBasisFromAnyRotation) {
  const Model m = model({2, 2, 2, 2, 2}, 40);  // a 5-fold multiplet, like a sphere's n = 2
  const Eigen::MatrixXd U = m.E.leftCols(5);
  const Eigen::MatrixXd reference = apply_rule(m, U, 1e-8);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Eigen::MatrixXd rotated = apply_rule(m, U * random_orthogonal(5, seed), 1e-8);
    EXPECT_LE((rotated - reference).norm(), 1e-12) << "seed " << seed;
  }
  EXPECT_LE((reference.transpose() * reference - Eigen::MatrixXd::Identity(5, 5)).norm(), 1e-12);  // M-orthonormal
}

TEST(ModeBasis, SplitClusterGivesItsEigenvectorsWithTheSignRule) {
  const Model m = model({2.0, 2.002, 2.005}, 30);  // split by 0.1 %: Ritz vectors are the eigenvectors
  const Eigen::MatrixXd U = m.E.leftCols(3);
  const Eigen::MatrixXd a = apply_rule(m, U * random_orthogonal(3, 3), 1e-8);
  const Eigen::MatrixXd b = apply_rule(m, -U * random_orthogonal(3, 4), 1e-8);
  EXPECT_LE((a - b).norm(), 1e-10);
  for (int k = 0; k < 3; ++k) {  // each column is +-E_k, and its largest reference projection is positive
    EXPECT_NEAR(std::abs(a.col(k).dot(m.E.col(k))), 1.0, 1e-10);
    const Eigen::RowVectorXd c = a.col(k).transpose() * m.G;
    Eigen::Index at = 0;
    c.cwiseAbs().maxCoeff(&at);
    EXPECT_GT(c(at), 0);
  }
}

TEST(ModeBasis, RitzValuesAreTheEigenvalues) {
  const Model m = model({1.0, 1.5, 1.5}, 20);
  const Eigen::MatrixXd U = m.E.leftCols(3) * random_orthogonal(3, 9);
  const Eigen::MatrixXd A = U.transpose() * m.K * U, B = U.transpose() * U, C = U.transpose() * m.G;
  const auto basis = cluster_basis(A, B, C, 1e-8);
  ASSERT_EQ(basis.lambdas.size(), 3u);
  EXPECT_NEAR(basis.lambdas[0], 1.0, 1e-12);
  EXPECT_NEAR(basis.lambdas[2], 1.5, 1e-12);
  EXPECT_EQ(basis.degenerate_groups, 1);
}

TEST(ModeBasis, ClustersByRelativeGap) {
  const std::vector<double> f{1.0, 1.001, 1.1, 2.0, 2.0005, 2.0009};
  const auto c = clusters_by_gap(f, 5e-3);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], std::make_pair(0, 2));
  EXPECT_EQ(c[1], std::make_pair(2, 3));
  EXPECT_EQ(c[2], std::make_pair(3, 6));
}

TEST(ModeBasis, ReferenceFieldsAreTheGradedMonomials) {
  const Eigen::Vector3d x(0.5, -2.0, 3.0);
  EXPECT_EQ(reference_field(0, x), Eigen::Vector3d(1, 0, 0));   // 1 e_x
  EXPECT_EQ(reference_field(5, x), Eigen::Vector3d(0, 0, 0.5)); // x e_z
  EXPECT_EQ(reference_field(59, x), Eigen::Vector3d(0, 0, 27)); // z^3 e_z
}

}  // namespace
