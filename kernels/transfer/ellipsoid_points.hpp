#pragma once
// Points on an ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 for the exterior solve: a Gauss-Legendre
// product grid on the first octant in the angles of x = a sin u cos v, y = b sin u sin v,
// z = c cos u, with area weights; the other seven octants are its mirror images, so every field
// splits into 8 parity classes that are solved on the octant alone (docs/transfer.md).
#include <Eigen/Core>
#include <array>
#include <vector>

namespace clatter::kernels::transfer {

struct SurfacePoints {
  std::vector<Eigen::Vector3d> position_m, normal;  // normal: outward, unit
  std::vector<double> weight_m2;                     // quadrature weight (area) of each point
  std::size_t size() const { return position_m.size(); }
};

// n_u x n_v points strictly inside the first octant (none on a mirror plane).
SurfacePoints octant_grid(const std::array<double, 3>& axes_m, int n_u, int n_v);

// The octant's extent along each grid angle [m]: the longer of the quarter meridians (a, c) and
// (b, c), and the quarter equator (a, b).
std::array<double, 2> octant_lengths_m(const std::array<double, 3>& axes_m);

// The smaller principal radius of curvature at the point x of the ellipsoid (from its Gaussian
// and mean curvature, K = 1 / (a^2 b^2 c^2 h^4), |H| = (a^2 + b^2 + c^2 - |x|^2) / (2 a^2 b^2 c^2 h^3),
// h^2 = x^2/a^4 + y^2/b^4 + z^2/c^4).
double min_curvature_radius_m(const std::array<double, 3>& axes_m, const Eigen::Vector3d& x);

// The depth of the source layer below x: depth x min(a, max(R_min(x), a / 2)). It follows the
// surface and comes nearer where it curves sharply (a pancake's rim, a cigar's tips), but not
// below a/2 x depth: a layer as near as a thin rim's own radius would need sources that close all
// along it.
double layer_depth_m(const std::array<double, 3>& axes_m, const Eigen::Vector3d& x, double depth);

// The points moved inward along their normals by layer_depth_m, shortened where the normal would
// leave a thin body through its other face (near a rim sharper than a/2). Weights are kept
// (unused for sources).
SurfacePoints inner_layer(const std::array<double, 3>& axes_m, const SurfacePoints& surface, double depth);

// Points per grid angle for that layer such that neighbouring sources are nowhere farther apart
// than min(spacing_cap_m, their depth below the surface): a source at depth D smooths the surface
// over about D, so sources D apart leave ripples of e^(-2 pi) ~ 0.2 % and no gaps, also where
// the layer comes close to a sharply curved rim. At least `minimum`.
std::array<int, 2> inner_layer_counts(const std::array<double, 3>& axes_m, double depth, double spacing_cap_m,
                                      int minimum);

// Points in angles with the pole on the thin axis, x = a cos t, y = b sin t cos p, z = c sin t sin p
// (t, p in (0, pi/2)): Gauss-Legendre rows in t, row i with per_row[i] Gauss-Legendre points in p,
// with area weights. At fixed p, t is the eccentric anomaly of the meridian ellipse through the
// rim (t = pi/2), so for confocal ellipsoids the same (t, p) pair points across the thin gap the
// way elliptic coordinates do: rows can follow the rim without the z pole of octant_grid on it.
// `midpoint`: equally spaced angles (the midpoint rule) instead of Gauss-Legendre nodes, for
// sources, whose largest gap, not a quadrature, is what matters (Gauss-Legendre's middle gaps are
// pi / 2 times the mean).
SurfacePoints rim_grid(const std::array<double, 3>& axes_m, const std::vector<int>& per_row, bool midpoint = false);

// rim_grid's extent along each angle [m]: the longest quarter meridian (a, c), and the quarter
// rim (b, c).
std::array<double, 2> rim_lengths_m(const std::array<double, 3>& axes_m);

// The ellipsoid confocal with axes_m whose thin semi-axis is t a (0 < t <= 1): semi-axes
// sqrt(axes^2 - (1 - t^2) a^2). Its rim lies (1 - t^2) a^2 / (2 b) inside the rim of axes_m, a
// fixed fraction of the rim's own curvature radius a^2 / b, and its faces (1 - t) a inside.
std::array<double, 3> confocal_axes_m(const std::array<double, 3>& axes_m, double t);

// Mirror image s in 0..7: bit 0 flips x, bit 1 y, bit 2 z.
inline Eigen::Vector3d mirror(const Eigen::Vector3d& x, int s) {
  return {(s & 1) ? -x.x() : x.x(), (s & 2) ? -x.y() : x.y(), (s & 4) ? -x.z() : x.z()};
}

// The sign a field of parity class `sigma` (bit set: odd in that coordinate) takes under mirror s.
inline double parity_sign(int s, int sigma) { return __builtin_popcount(static_cast<unsigned>(s & sigma)) % 2 ? -1.0 : 1.0; }

}  // namespace clatter::kernels::transfer
