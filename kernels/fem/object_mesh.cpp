// TEMPORARY STUB (replaced by the object mesher).
#include "kernels/fem/object_mesh.hpp"

#include <algorithm>
#include <map>

#include "kernels/fem/lowest_mode.hpp"

namespace clatter::kernels::fem {

ObjectMesh mesh_object(const std::vector<std::array<double, 3>>& vertices_m, const std::vector<std::array<int, 3>>& triangles,
                       const ObjectMeshSettings& settings, const EllipsoidMeshBounds&) {
  ObjectMesh out;
  out.mesh = tetrahedralize_surface(vertices_m, triangles, settings.edge_length_m);
  // faces of each tet: (0,1,2) opposite 3 etc, with mid-nodes; outward orientation for positive tets:
  // face opposite vertex 3 is (0,2,1), opposite 2: (0,1,3), opposite 1: (0,3,2), opposite 0: (1,2,3).
  // mid-node index of edge (a,b):
  auto mid = [](int a, int b) {
    const int lo = std::min(a, b), hi = std::max(a, b);
    if (lo == 0 && hi == 1) return 4;
    if (lo == 1 && hi == 2) return 5;
    if (lo == 0 && hi == 2) return 6;
    if (lo == 0 && hi == 3) return 7;
    if (lo == 1 && hi == 3) return 8;
    return 9;
  };
  const std::array<std::array<int, 3>, 4> faces{{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};
  std::map<std::array<int, 3>, std::pair<int, BoundaryFace>> count;
  for (const auto& e : out.mesh.elements)
    for (const auto& f : faces) {
      BoundaryFace b{e[f[0]], e[f[1]], e[f[2]], e[mid(f[0], f[1])], e[mid(f[1], f[2])], e[mid(f[2], f[0])]};
      std::array<int, 3> key{b[0], b[1], b[2]};
      std::sort(key.begin(), key.end());
      auto& c = count[key];
      ++c.first;
      c.second = b;
    }
  for (const auto& [k, c] : count)
    if (c.first == 1) out.boundary.push_back(c.second);
  out.quality = mesh_quality(out.mesh);
  out.quality.edge_length_m = settings.edge_length_m;
  return out;
}

std::string solid_mesh_problem(const std::vector<std::array<double, 3>>& vertices_m,
                               const std::vector<std::array<int, 3>>& triangles, double) {
  if (enclosed_volume_m3(vertices_m, triangles) <= 0) return "the faces point inward";
  return "";
}

}  // namespace clatter::kernels::fem
