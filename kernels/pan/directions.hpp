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

}  // namespace clatter::kernels::pan
