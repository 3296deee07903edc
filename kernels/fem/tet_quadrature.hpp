#pragma once
// Quadrature on the reference tetrahedron {xi, eta, zeta >= 0, xi + eta + zeta <= 1} (volume 1/6):
// sum_q weights[q] f(points[q]) = integral of f, exactly for every polynomial of total degree <= degree.
#include <array>
#include <vector>

namespace clatter::kernels::fem {

using RefPoint = std::array<double, 3>;  // (xi, eta, zeta), dimensionless

struct TetQuadrature {
  std::vector<RefPoint> points;
  std::vector<double> weights;  // sum to 1/6
  int degree = 0;
};

// Keast (1986), "Moderate-degree tetrahedral quadrature formulas", CMAME 55, 339-348:
// the 4-point rule of degree 2 (the P2 stiffness of a straight element), and the 15-point rule of
// degree 5 with positive weights (Keast's #6), which covers the degree-4 P2 mass with one degree to
// spare for the rational integrands of curved elements.
const TetQuadrature& keast_degree2();
const TetQuadrature& keast_degree5();

// A collapsed-coordinate (Duffy) product of Gauss-Legendre rules, exact to any `degree` >= 0 with
// positive weights (the Gauss-Legendre form of Stroud's conical product rule, Stroud 1971, §2.7;
// Karniadakis & Sherwin 2005, §4.1): the high-order rule for checks and strongly curved elements.
TetQuadrature collapsed_gauss(int degree);

// n-point Gauss-Legendre nodes and weights on [0, 1].
void gauss_legendre_unit(int n, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace clatter::kernels::fem
