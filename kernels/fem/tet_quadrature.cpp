#include "kernels/fem/tet_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::kernels::fem {
namespace {

// Every distinct permutation of the barycentric point (l0, l1, l2, l3), as (l1, l2, l3).
void add_orbit(TetQuadrature& rule, std::array<double, 4> l, double weight) {
  std::sort(l.begin(), l.end());
  do {
    rule.points.push_back({l[1], l[2], l[3]});
    rule.weights.push_back(weight);
  } while (std::next_permutation(l.begin(), l.end()));
}

TetQuadrature make_keast_degree2() {
  TetQuadrature rule;
  rule.degree = 2;
  const double s5 = std::sqrt(5.0);
  const double a = (5 - s5) / 20, b = (5 + 3 * s5) / 20;
  add_orbit(rule, {a, a, a, b}, 1.0 / 24);
  return rule;
}

TetQuadrature make_keast_degree5() {
  TetQuadrature rule;
  rule.degree = 5;
  // Keast's tabulated values carry 15 digits; these were refined by Newton's method on the
  // moment equations so that the monomial checks hold to rounding.
  const double a = 0.06655015357366455, b = 0.5 - a;
  add_orbit(rule, {0.25, 0.25, 0.25, 0.25}, 0.03028367809708906);
  add_orbit(rule, {0.0, 1.0 / 3, 1.0 / 3, 1.0 / 3}, 27.0 / 4480);
  add_orbit(rule, {1.0 / 11, 1.0 / 11, 1.0 / 11, 8.0 / 11}, 0.011645249086028962);
  add_orbit(rule, {a, a, b, b}, 0.01094914156138654);
  return rule;
}

}  // namespace

void gauss_legendre_unit(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  if (n < 1) throw std::invalid_argument("gauss_legendre_unit: n = " + std::to_string(n) + " < 1");
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    // Newton on P_n from the Chebyshev-like first guess converges for every root.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    nodes[static_cast<std::size_t>(i)] = 0.5 * (1 - x);
    weights[static_cast<std::size_t>(i)] = 1.0 / ((1 - x * x) * dp * dp);  // 2/((1-x^2)P'^2), halved
  }
}

TetQuadrature collapsed_gauss(int degree) {
  if (degree < 0) throw std::invalid_argument("collapsed_gauss: negative degree");
  // xi = u, eta = v (1 - u), zeta = w (1 - u)(1 - v), Jacobian (1 - u)^2 (1 - v): a degree-p
  // polynomial becomes degree p + 2 in u, so n Gauss points (exact to 2n - 1) need 2n - 1 >= p + 2.
  const int n = (degree + 4) / 2;
  std::vector<double> x, w;
  gauss_legendre_unit(n, x, w);
  TetQuadrature rule;
  rule.degree = degree;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < x.size(); ++j)
      for (std::size_t k = 0; k < x.size(); ++k) {
        const double u = x[i], v = x[j], s = x[k];
        rule.points.push_back({u, v * (1 - u), s * (1 - u) * (1 - v)});
        rule.weights.push_back(w[i] * w[j] * w[k] * (1 - u) * (1 - u) * (1 - v));
      }
  return rule;
}

const TetQuadrature& keast_degree2() {
  static const TetQuadrature rule = make_keast_degree2();
  return rule;
}

const TetQuadrature& keast_degree5() {
  static const TetQuadrature rule = make_keast_degree5();
  return rule;
}

}  // namespace clatter::kernels::fem
