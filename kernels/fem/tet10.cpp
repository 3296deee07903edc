#include "kernels/fem/tet10.hpp"

#include <Eigen/Dense>
#include <string>
#include <utility>

namespace clatter::kernels::fem {
namespace {

std::array<double, 4> barycentric(const RefPoint& p) { return {1 - p[0] - p[1] - p[2], p[0], p[1], p[2]}; }

// d L_a / d(xi, eta, zeta) for the four barycentric coordinates.
constexpr std::array<std::array<double, 3>, 4> kBaryGradient = {{{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

// det J at a quadrature point, or InvertedElement.
double checked_det(const Eigen::Matrix3d& j, int q) {
  const double det = j.determinant();
  if (!(det > 0)) throw InvertedElement(q, det);
  return det;
}

}  // namespace

InvertedElement::InvertedElement(int q, double det)
    : std::domain_error("tet10: inverted element (det J = " + std::to_string(det) + " m^3 at quadrature point " +
                        std::to_string(q) + ")"),
      quadrature_point(q),
      det_jacobian_m3(det) {}

Tet10Shape tet10_shape(const RefPoint& p) {
  const auto l = barycentric(p);
  Tet10Shape n;
  for (int i = 0; i < 4; ++i) n(i) = l[i] * (2 * l[i] - 1);
  for (int e = 0; e < 6; ++e) n(4 + e) = 4 * l[kTet10Edges[e][0]] * l[kTet10Edges[e][1]];
  return n;
}

Tet10Gradient tet10_shape_gradient(const RefPoint& p) {
  const auto l = barycentric(p);
  Tet10Gradient g;
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 4; ++i) g(i, k) = (4 * l[i] - 1) * kBaryGradient[i][k];
    for (int e = 0; e < 6; ++e) {
      const int a = kTet10Edges[e][0], b = kTet10Edges[e][1];
      g(4 + e, k) = 4 * (kBaryGradient[a][k] * l[b] + l[a] * kBaryGradient[b][k]);
    }
  }
  return g;
}

RefPoint tet10_reference_node(int i) {
  static constexpr std::array<RefPoint, 4> kVertex = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  if (i < 4) return kVertex[i];
  const auto& a = kVertex[kTet10Edges[i - 4][0]];
  const auto& b = kVertex[kTet10Edges[i - 4][1]];
  return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
}

Tet10Coords tet10_straight(const Eigen::Matrix<double, 3, 4>& v) {
  Tet10Coords x;
  x.leftCols<4>() = v;
  for (int e = 0; e < 6; ++e) x.col(4 + e) = 0.5 * (v.col(kTet10Edges[e][0]) + v.col(kTet10Edges[e][1]));
  return x;
}

Eigen::Matrix3d tet10_jacobian(const Tet10Coords& x, const RefPoint& p) { return x * tet10_shape_gradient(p); }

double tet10_volume_m3(const Tet10Coords& x, const TetQuadrature& rule) {
  double v = 0;
  for (std::size_t q = 0; q < rule.points.size(); ++q)
    v += rule.weights[q] * checked_det(tet10_jacobian(x, rule.points[q]), static_cast<int>(q));
  return v;
}

Tet10Matrix tet10_stiffness(const Tet10Coords& x, const model::Material& m, const TetQuadrature& rule) {
  // The rules of E and nu (not the density's: the stiffness has none), without copying the material.
  for (const auto& [key, value] : {std::pair<const char*, double>{"youngs_pa", m.youngs_pa}, {"poisson", m.poisson}})
    if (const char* broken = model::material_rule(key, value))
      throw std::invalid_argument(std::string("tet10_stiffness: ") + key + " = " + std::to_string(value) + ": " + broken);
  // Voigt order (xx, yy, zz, yz, xz, xy) with engineering shears, so strain energy = e^T D e / 2.
  Eigen::Matrix<double, 6, 6> d = Eigen::Matrix<double, 6, 6>::Zero();
  d.topLeftCorner<3, 3>().setConstant(m.lame_lambda_pa());
  for (int i = 0; i < 3; ++i) d(i, i) += 2 * m.shear_modulus_pa();
  for (int i = 3; i < 6; ++i) d(i, i) = m.shear_modulus_pa();
  Tet10Matrix k = Tet10Matrix::Zero();
  Eigen::Matrix<double, 6, kTet10Dofs> b;
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const Tet10Gradient g_ref = tet10_shape_gradient(rule.points[q]);
    const Eigen::Matrix3d j = x * g_ref;
    const double det = checked_det(j, static_cast<int>(q));
    const Tet10Gradient g = g_ref * j.inverse();  // dN_i / dx_k
    b.setZero();
    for (int i = 0; i < kTet10Nodes; ++i) {
      const int c = 3 * i;
      b(0, c) = g(i, 0);
      b(1, c + 1) = g(i, 1);
      b(2, c + 2) = g(i, 2);
      b(3, c + 1) = g(i, 2);
      b(3, c + 2) = g(i, 1);
      b(4, c) = g(i, 2);
      b(4, c + 2) = g(i, 0);
      b(5, c) = g(i, 1);
      b(5, c + 1) = g(i, 0);
    }
    k.noalias() += (rule.weights[q] * det) * (b.transpose() * d * b);
  }
  return 0.5 * (k + k.transpose());  // exactly symmetric despite rounding in the products
}

Tet10Matrix tet10_mass(const Tet10Coords& x, double rho_kg_m3, const TetQuadrature& rule) {
  Eigen::Matrix<double, kTet10Nodes, kTet10Nodes> scalar = Eigen::Matrix<double, kTet10Nodes, kTet10Nodes>::Zero();
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const double det = checked_det(tet10_jacobian(x, rule.points[q]), static_cast<int>(q));
    const Tet10Shape n = tet10_shape(rule.points[q]);
    scalar.noalias() += (rule.weights[q] * det * rho_kg_m3) * (n * n.transpose());
  }
  // The same scalar mass on each displacement component.
  Tet10Matrix m = Tet10Matrix::Zero();
  for (int i = 0; i < kTet10Nodes; ++i)
    for (int j = 0; j < kTet10Nodes; ++j)
      for (int c = 0; c < 3; ++c) m(3 * i + c, 3 * j + c) = scalar(i, j);
  return m;
}

}  // namespace clatter::kernels::fem
