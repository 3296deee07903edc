#pragma once
// Listening directions of a PAN proxy (Chadwick et al. 2012, section 5): the positive octant of
// the unit sphere, triangulated by cutting each edge of the spherical triangle (x, y, z axes) into
// d parts: (d+1)(d+2)/2 vertices, d^2 triangles; the paper's d = 8 gives 45 and 64. A direction
// is located by its gnomonic projection onto the plane x + y + z = 1 and interpolated linearly
// (barycentric) over its triangle.
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

struct DirectionWeights {
  std::array<int, 3> vertex{};
  std::array<double, 3> weight{};  // non-negative, sum 1
};

// For a direction in the closed positive octant (components >= 0, not all 0).
DirectionWeights locate_direction(const std::array<double, 3>& d, int divisions = kPaperDivisions);

}  // namespace clatter::kernels::pan
