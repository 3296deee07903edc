#pragma once
// The 10-node (quadratic, isoparametric) tetrahedron for isotropic linear elasticity: shape
// functions, the map from the reference element, and the 30x30 element stiffness and consistent
// mass matrices (docs/validation.md, "The FEM element").
//
// Node order (VTK_QUADRATIC_TETRA, also TetGen's -o2 output): vertices 0-3, then the mid-nodes of
// the edges 01, 12, 20, 03, 13, 23 as nodes 4-9. Reference vertices: 0 = (0,0,0), 1 = (1,0,0),
// 2 = (0,1,0), 3 = (0,0,1). Degrees of freedom are node-major: (u0x, u0y, u0z, u1x, ...).
// Mid-nodes may sit off the straight edges (curved elements), so the Jacobian varies inside.
#include <array>
#include <stdexcept>

#include <Eigen/Core>

#include "kernels/fem/tet_quadrature.hpp"

#include "model/material.hpp"

namespace clatter::kernels::fem {

inline constexpr int kTet10Nodes = 10;
inline constexpr int kTet10Dofs = 30;
inline constexpr std::array<std::array<int, 2>, 6> kTet10Edges = {{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};

using Tet10Coords = Eigen::Matrix<double, 3, kTet10Nodes>;  // node positions in columns, metres
using Tet10Shape = Eigen::Matrix<double, kTet10Nodes, 1>;
using Tet10Gradient = Eigen::Matrix<double, kTet10Nodes, 3>;  // row i: dN_i / d(xi, eta, zeta)
using Tet10Matrix = Eigen::Matrix<double, kTet10Dofs, kTet10Dofs>;

Tet10Shape tet10_shape(const RefPoint& p);
Tet10Gradient tet10_shape_gradient(const RefPoint& p);
// The reference coordinates of node i (mid-nodes at the edge midpoints).
RefPoint tet10_reference_node(int i);
// A straight element: the mid-nodes at the midpoints of the vertices' edges (columns 0-3 used).
Tet10Coords tet10_straight(const Eigen::Matrix<double, 3, 4>& vertices_m);

// J = dx / d(xi, eta, zeta) at p (J(i, k) = dx_i / dxi_k).
Eigen::Matrix3d tet10_jacobian(const Tet10Coords& x_m, const RefPoint& p);

// An element whose Jacobian determinant is not positive at some quadrature point (inverted or
// degenerate): integrating it would give a matrix with the wrong sign of energy.
class InvertedElement : public std::domain_error {
 public:
  InvertedElement(int quadrature_point, double det_jacobian_m3);
  int quadrature_point;
  double det_jacobian_m3;
};

// Volume (m^3), stiffness K_e (N/m) and consistent mass M_e (kg) by the given rule; each throws
// InvertedElement rather than integrate a non-positive Jacobian.
double tet10_volume_m3(const Tet10Coords& x_m, const TetQuadrature& rule = keast_degree5());
// The stiffness takes E and nu of `material` (its Lamé constants); std::invalid_argument when
// they are not an elastic solid's (model::check_material, density aside).
Tet10Matrix tet10_stiffness(const Tet10Coords& x_m, const model::Material& material,
                            const TetQuadrature& rule = keast_degree5());
Tet10Matrix tet10_mass(const Tet10Coords& x_m, double rho_kg_m3, const TetQuadrature& rule = keast_degree5());

}  // namespace clatter::kernels::fem
