#pragma once
// Listening directions of a PAN proxy (Chadwick et al. 2012, section 5): the positive octant of
// the unit sphere, triangulated by cutting each edge of the spherical triangle (x, y, z axes) into
// d parts: (d+1)(d+2)/2 vertices, d^2 triangles; the paper's d = 8 gives 45 and 64. A direction
// is located by its gnomonic projection onto the plane x + y + z = 1 and interpolated over the
// triangulation, either linearly (barycentric, the paper's choice) or quadratically: for even d the
// same vertices are the nodes of (d/2)^2 six-node quadratic triangles, each the union of four of
// the d^2 triangles. Rotation fields of elongated proxies vary too fast across the paper's 11-degree
// triangles for linear interpolation (6-9 % between vertices, docs/pan.md); quadratic brings them
// within 4 % from the same data.
#include <array>
#include <vector>

namespace clatter::kernels::pan {

inline constexpr int kPaperDivisions = 8;
inline constexpr int vertex_count(int divisions) { return (divisions + 1) * (divisions + 2) / 2; }
// Inverse of vertex_count; 0 if n is not a vertex count.
int divisions_of(std::size_t n_vertices);

// Unit vectors of the vertices, index order (a, b) row-major with c = d - a - b.
std::vector<std::array<double, 3>> direction_vertices(int divisions = kPaperDivisions);
// The triangles as vertex indices.
std::vector<std::array<int, 3>> direction_triangles(int divisions = kPaperDivisions);

enum class Interpolation { linear, quadratic };

struct DirectionWeights {
  int count = 0;  // 3 (linear) or 6 (quadratic) entries are used
  std::array<int, 6> vertex{};
  std::array<double, 6> weight{};  // sum 1; linear: non-negative; quadratic: may be negative
};

// For a direction in the closed positive octant (components >= 0, not all 0). Quadratic needs an
// even `divisions`.
DirectionWeights locate_direction(const std::array<double, 3>& d, int divisions = kPaperDivisions,
                                  Interpolation interpolation = Interpolation::quadratic);

// A rigid-body field is odd across the mirror planes of eqs. (16)-(21) where its parity is -1 (a
// translation along x across x = 0; a rotation about x across y = 0 and z = 0), so in the positive
// octant it vanishes on those planes like the product of the direction's components across them.
// Relative to the field, interpolation between directions is worst right there (issue 32: every
// held-out miss above 5 % of the (0.2625, 0.12) proxy lay 5 degrees off such a plane), so the
// bank stores q = p / symmetry_zeros(field, d), which is even across each plane and does not
// vanish on it, and the evaluator multiplies back. d: a unit direction in the closed octant.
double symmetry_zeros(int field, const std::array<double, 3>& d);
// Where symmetry_zeros vanishes q is its limit; a direction on such a plane is heard kOffPlane
// off it instead (q is even across the plane, so the offset costs O(kOffPlane^2), 1e-4 relative).
inline constexpr double kOffPlane = 0.01;
std::array<double, 3> off_planes(int field, const std::array<double, 3>& d);

}  // namespace clatter::kernels::pan
