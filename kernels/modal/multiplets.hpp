#pragma once
// Physical multiplets of an ellipsoid's modes, decided by its symmetry and the mode shapes, not by
// a frequency gap (docs/modal.md "Multiplets"). A triaxial ellipsoid (D2h, one-dimensional
// irreducible representations only) has no degenerate modes; a spheroid (two equal axes) has
// doublets of azimuthal order |m| >= 1 and singles m = 0 about its axis; a sphere has multiplets of
// 2n + 1 members of degree n.
//
// The rotation generator about a unit axis e acts on a displacement field as
//   (J_e u)(x) = e x u(x) - d/dphi u(x),   d/dphi = (e x x) . grad,
// the derivative of R(alpha) u(R(alpha)^T x) at alpha = 0. On a surface of revolution about e it
// is skew-adjoint in the surface L2 product, and it maps a degenerate eigenspace onto itself. For
// the modes U of a cluster (neighbours within the cluster gap, which holds the mesh-split members
// of every multiplet) on the bank's curved surface mesh, with G = U^T W U (W: the surface
// integral, 6-point rule on the quadratic faces) and G = L L^T, the matrix of J_e on their span,
// A_e = L^-1 U^T W J_e U L^-T, has eigenvalues +-i m, and the sphere's Casimir
// -(A_x^2 + A_y^2 + A_z^2) eigenvalues n (n + 1). Taken as L^-1 (sum_e (J_e U)^T W (J_e U)) L^-T,
// equal to -sum_e A_e^2 where the span is invariant, it also shows a span that is not: a lone member
// of a doublet keeps its m^2 (the compressed -A_e^2 would give it 0). The eigenspaces give each mode
// an order by its largest weight, the counts fixed by the rounded eigenvalues; within a cluster,
// modes of one order form multiplets of 2 (|m| >= 1) or 1 (m = 0), or 2n + 1, in frequency order.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace clatter::kernels::modal {

enum class SymmetryKind { none, spheroid, sphere };

struct EllipsoidSymmetry {
  SymmetryKind kind = SymmetryKind::none;
  int axis = -1;  // spheroid: the axis of revolution (0 x, 1 y, 2 z), the one semi-axis unlike the others
};

// From the semi-axes: two equal (relative difference <= tolerance) make a spheroid, three a sphere.
EllipsoidSymmetry ellipsoid_symmetry(const std::array<double, 3>& semi_axes_m, double tolerance = 1e-9);

struct Multiplets {
  std::vector<std::int32_t> multiplet;  // per mode: its multiplet, 0-based, numbered by lowest member
  std::vector<std::int32_t> order;      // per mode: |m| (spheroid), n (sphere), -1 (no symmetry)
  double order_defect = 0;              // largest distance of a computed |m| or n from its integer
  int incomplete = 0;                   // multiplets with fewer members than the symmetry demands
};

// `nodes_m`, `faces`: the curved 6-node surface (vertices counter-clockwise from outside, then
// the mid-nodes of edges 01, 12, 20), centred on the origin with the ellipsoid's axes along x, y,
// z. `shapes`: [mode][node][3]. `cluster`: per mode, its cluster, numbered in order (consecutive
// modes of one cluster). Throws std::invalid_argument on inconsistent sizes.
Multiplets find_multiplets(std::span<const std::array<double, 3>> nodes_m,
                           std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shapes,
                           std::span<const std::int32_t> cluster, const EllipsoidSymmetry& symmetry);

}  // namespace clatter::kernels::modal
