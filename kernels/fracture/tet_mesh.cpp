#include "kernels/fracture/tet_mesh.hpp"

#include <algorithm>
#include <utility>

#include "kernels/fem/lowest_mode.hpp"

namespace clatter::kernels::fracture {

double tet_volume_m3(const TetMesh& mesh, int t) {
  const auto& n = mesh.tets[t];
  const Vec3& x0 = mesh.nodes_m[n[0]];
  return dot(sub(mesh.nodes_m[n[1]], x0), cross(sub(mesh.nodes_m[n[2]], x0), sub(mesh.nodes_m[n[3]], x0))) / 6;
}

std::vector<BoundaryFace> boundary_faces(const TetMesh& mesh) {
  // Local faces opposite vertex 0..3, counter-clockwise seen from outside a positive tetrahedron.
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  // One sorted array of (sorted nodes, tet*4 + face) rather than a map: the fracture pattern calls
  // this on every piece, hundreds of thousands of tetrahedra in all.
  std::vector<std::pair<std::array<int, 3>, int>> keys;
  keys.reserve(mesh.tets.size() * 4);
  for (std::size_t i = 0; i < mesh.tets.size(); ++i)
    for (int f = 0; f < 4; ++f) {
      const auto& t = mesh.tets[i];
      std::array<int, 3> key{t[kFace[f][0]], t[kFace[f][1]], t[kFace[f][2]]};
      std::sort(key.begin(), key.end());
      keys.emplace_back(key, static_cast<int>(i * 4 + f));
    }
  std::sort(keys.begin(), keys.end());
  std::vector<char> single(keys.size(), 0);
  for (std::size_t a = 0, b = 0; a < keys.size(); a = b) {
    for (b = a + 1; b < keys.size() && keys[b].first == keys[a].first; ++b) {
    }
    if (b == a + 1) single[keys[a].second] = 1;
  }
  std::vector<BoundaryFace> out;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i)
    for (int f = 0; f < 4; ++f)
      if (single[i * 4 + f]) {
        const auto& t = mesh.tets[i];
        out.push_back({{t[kFace[f][0]], t[kFace[f][1]], t[kFace[f][2]]}, static_cast<int>(i)});
      }
  return out;
}

TetMesh tetrahedralize(const std::vector<Vec3>& vertices_m, const std::vector<std::array<int, 3>>& triangles,
                       double edge_length_m) {
  fem::LinearMesh linear = fem::tetrahedralize_linear(vertices_m, triangles, edge_length_m);
  TetMesh mesh;
  mesh.nodes_m = std::move(linear.points);
  mesh.tets = std::move(linear.tets);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    if (tet_volume_m3(mesh, static_cast<int>(t)) < 0) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
  return mesh;
}

}  // namespace clatter::kernels::fracture
