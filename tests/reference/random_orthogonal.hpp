#pragma once
// A seeded random n x n orthogonal matrix (QR of a Gaussian matrix): the arbitrary basis rotation
// the basis-rule and multiplet tests feed in.
#include <Eigen/Dense>

#include <random>

namespace clatter::reference {

inline Eigen::MatrixXd random_orthogonal(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = normal(gen);
  return Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
}

}  // namespace clatter::reference
