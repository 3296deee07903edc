#pragma once
// Closed, outward-oriented triangle meshes built in the tests (no files): an axis-aligned box, an
// icosphere, a box with one corner cut off (no mirror symmetry), a square pyramid (two planes), plus the exact cross-section
// of a closed mesh by an axis plane (area and first moments), for divergence-theorem checks.
#include <array>
#include <vector>

namespace clatter::reference {

struct Mesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
};

// The box |x| <= hx, |y| <= hy, |z| <= hz, each face two triangles.
Mesh box_mesh(double hx, double hy, double hz);
// The icosahedron subdivided `levels` times (20 * 4^levels triangles), vertices on the sphere of
// radius `radius`, then scaled by (sx, sy, sz).
Mesh icosphere(double radius, int levels, double sx = 1, double sy = 1, double sz = 1);
// The cube |x|, |y|, |z| <= h with the corner (h, h, h) cut off by the plane x + y + z = 3h - cut.
Mesh cut_cube(double h, double cut);
// The square pyramid over |x|, |y| <= half_base at z = -height / 4 with its apex at z = 3 height / 4
// (its centroid at the origin): mirror-symmetric in x and y, not in z.
Mesh square_pyramid(double half_base, double height);

// The section of the solid bounded by `mesh` with the plane x[axis] = at: its area and the
// integral of the position over it (3 components), from the segments in which the triangles cross
// the plane (Green's theorem). No vertex may lie on the plane.
struct Section {
  double area = 0;
  std::array<double, 3> moment{};
};
Section mesh_section(const Mesh& mesh, int axis, double at);

}  // namespace clatter::reference
