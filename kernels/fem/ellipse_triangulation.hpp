#pragma once
// A quality triangulation of the ellipse y^2/b^2 + z^2/c^2 <= 1: the mid-plane of a flat
// ellipsoid, which kernels/fem/layered_ellipsoid.cpp extrudes through the thickness. CGAL's
// Delaunay refinement with a size field (ellipse_triangulation.cpp, the only file that sees CGAL).
#include <array>
#include <functional>
#include <vector>

namespace clatter::kernels::fem {

struct EllipseTriangulation {
  std::vector<std::array<double, 2>> points_m;  // (y, z)
  std::vector<std::array<int, 3>> triangles;    // counter-clockwise in (y, z)
  std::vector<char> on_rim;                     // per point: on the ellipse (the rim of the body)
  // Per point: rho of the ring it lies on (1 the rim, the band's rings; an edge between two points
  // of one ring follows the ring, an ellipse), 0 off the rings.
  std::vector<double> ring_rho;
};

// A band of rings along the rim: the rim's points at `spacing_m`, repeated on the ellipses
// rho = 1 - depth (rho^2 = y^2/b^2 + z^2/c^2) and joined by quadrilaterals cut in two. Where a
// function of rho changes fastest at the rim (the thickness of an ellipsoid, a sqrt(1 - rho^2)),
// rings graded toward it resolve it at a fraction of the triangles an isotropic grading needs.
struct RimBand {
  double spacing_m = 0;       // along the rim
  std::vector<double> depths;  // rising, in (0, 1); empty: no band
};

// Inside the band (or the rim), triangles whose edges are at most size_m(y, z) at their centroid
// and whose smallest angle is at least 20.7 degrees (the bound Delaunay refinement is proven to
// reach), joined to the band's innermost ring; rim points on the ellipse, spaced at most size_m (or
// the band's spacing) on it. Deterministic: the same arguments give the same triangulation.
// Throws std::invalid_argument for non-positive semi-axes, a size that is not positive on the rim
// or depths that do not rise within (0, 1).
EllipseTriangulation triangulate_ellipse(double b_m, double c_m, const std::function<double(double, double)>& size_m,
                                         const RimBand& band = {});

}  // namespace clatter::kernels::fem
