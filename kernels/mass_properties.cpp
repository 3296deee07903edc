#include "kernels/mass_properties.hpp"

#include <cmath>

namespace clatter::kernels {

MeshMassProperties mesh_mass_properties(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  // Reference point: the mean vertex, so a mesh far from the origin loses no digits to cancellation.
  Vec3 ref{};
  for (const auto& v : vertices)
    for (std::size_t i = 0; i < 3; ++i) ref[i] += v[i] / static_cast<double>(vertices.size());
  // For the tetrahedron (0, p1, p2, p3) with signed volume V and S = p1 + p2 + p3:
  //   integral of x_i = V S_i / 4,   integral of x_i x_j = V (sum_k p_k,i p_k,j + S_i S_j) / 20.
  double volume = 0, area = 0;
  Vec3 first{};
  Mat3 second{};
  for (const auto& t : triangles) {
    std::array<Vec3, 3> p{};
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t i = 0; i < 3; ++i) p[k][i] = vertices[static_cast<std::size_t>(t[k])][i] - ref[i];
    const double v = (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
                      p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) / 6.0;
    const Vec3 s{p[0][0] + p[1][0] + p[2][0], p[0][1] + p[1][1] + p[2][1], p[0][2] + p[1][2] + p[2][2]};
    volume += v;
    const Vec3 n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    area += 0.5 * std::sqrt(dot(n, n));
    for (std::size_t i = 0; i < 3; ++i) {
      first[i] += v * s[i] / 4.0;
      for (std::size_t j = 0; j < 3; ++j)
        second[i][j] += v * (p[0][i] * p[0][j] + p[1][i] * p[1][j] + p[2][i] * p[2][j] + s[i] * s[j]) / 20.0;
    }
  }
  MeshMassProperties out;
  out.volume_m3 = volume;
  out.surface_area_m2 = area;
  Vec3 c{};  // centroid relative to ref
  for (std::size_t i = 0; i < 3; ++i) {
    c[i] = volume != 0 ? first[i] / volume : 0;
    out.centroid_m[i] = ref[i] + c[i];
  }
  // Second moments about the centroid (parallel axes), then I = tr(C) 1 - C.
  Mat3 central{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) central[i][j] = second[i][j] - volume * c[i] * c[j];
  const double trace = central[0][0] + central[1][1] + central[2][2];
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) out.inertia_per_density_m5[i][j] = (i == j ? trace : 0.0) - central[i][j];
  return out;
}

}  // namespace clatter::kernels
