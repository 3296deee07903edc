#pragma once
// Listening directions of a PAN proxy (Chadwick et al. 2012, section 5): the positive octant of
// the unit sphere, triangulated by cutting each edge of the spherical triangle (x, y, z axes) into
// 8: 45 vertices, 64 triangles. A direction is located by its gnomonic projection onto the plane
// x + y + z = 1 and interpolated linearly (barycentric) over its triangle.
#include <array>
#include <vector>

namespace clatter::kernels::pan {

inline constexpr int kDivisions = 8;
inline constexpr int kVertices = (kDivisions + 1) * (kDivisions + 2) / 2;  // 45
inline constexpr int kTriangles = kDivisions * kDivisions;                   // 64

// Unit vectors of the 45 vertices, index order (a, b) row-major with c = 8 - a - b.
const std::vector<std::array<double, 3>>& direction_vertices();
// The 64 triangles as vertex indices.
const std::vector<std::array<int, 3>>& direction_triangles();

struct DirectionWeights {
  std::array<int, 3> vertex{};
  std::array<double, 3> weight{};  // non-negative, sum 1
};

// For a direction in the closed positive octant (components >= 0, not all 0).
DirectionWeights locate_direction(const std::array<double, 3>& d);

}  // namespace clatter::kernels::pan
