#pragma once
// Closed, outward-wound triangle surfaces for the tests: an icosphere, boxes, an L-shaped prism,
// and the icosphere mapped onto an ellipsoid.
#include <array>
#include <vector>

namespace clatter::reference {

struct Surface {
  std::vector<std::array<double, 3>> vertices_m;
  std::vector<std::array<int, 3>> triangles;
};

// An icosahedron split `levels` times (20 * 4^levels triangles), vertices on the sphere.
Surface icosphere(double radius_m, int levels);
// The unit icosphere's vertices scaled to (x/a)^2 + (y/b)^2 + (z/c)^2 = 1.
Surface ellipsoid_surface(const std::array<double, 3>& semi_axes_m, int levels);
// [0, a] x [0, b] x [0, c], each face split into n x n squares of two triangles.
Surface box(double a_m, double b_m, double c_m, int n = 1);
// The L-shaped prism [0, 2w] x [0, w] x [0, h] united with [0, w] x [w, 2w] x [0, h], every face
// triangulated conformingly (the union of three w x w x h cells).
Surface l_prism(double w_m, double h_m);
Surface scaled(Surface s, double factor);

}  // namespace clatter::reference
