// TetGen's part of lowest_free_mode: the surface is checked here first, because TetGen given an
// open or inconsistent surface may fill a wrong region or fail with a bare exit code.
//
// TetGen switches, "pq1.5/12a<v>Q":
//   p      the input is a piecewise linear complex (the closed surface);
//   q      quality: radius-edge ratio <= 1.5, dihedral angles >= 12 degrees (no slivers: a sliver's
//          stiffness is near singular and spoils the factorization's accuracy);
//   a<v>   the volume of the regular tetrahedron of the target edge, so the interior is that coarse;
//   Q      quiet (a library prints no progress).
// No -Y: TetGen may split surface triangles, which the quality bound needs on thin debris.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "kernels/fem/lowest_mode.hpp"
#include "kernels/fem/mesh_check.hpp"
#include "kernels/fem/tetgen_fill.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

std::int64_t edge_key(int a, int b) { return static_cast<std::int64_t>(a) << 32 | static_cast<std::uint32_t>(b); }

[[noreturn]] void refuse(const std::string& why) { throw std::invalid_argument("lowest_free_mode: " + why); }

// Closed, manifold and consistently oriented (kernels/fem/mesh_check.hpp).
void check_surface(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  const std::string problem = surface_topology_problem(vertices, triangles);
  if (!problem.empty()) refuse(problem);
}

std::string tetgen_failure(int code) {
  switch (code) {
    case 1: return "TetGen ran out of memory";
    case 3: return "the surface intersects itself";
    case 4: return "the surface has a feature too small for TetGen's tolerance";
    case 5: return "the surface has two facets too close together";
    case 10: return "TetGen found an input error (duplicate or degenerate triangles?)";
    default: return "TetGen failed (code " + std::to_string(code) + ")";
  }
}

// TetGen's fill of the surface given by the used vertices only: a point on no facet would be
// inserted as an interior vertex or dropped, depending on where it lies.
LinearMesh run_tetgen(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles, double h_m) {
  std::vector<int> index(vertices.size(), -1);
  std::vector<P3> used;
  for (const auto& f : triangles)
    for (int v : f)
      if (index[v] < 0) {
        index[v] = static_cast<int>(used.size());
        used.push_back(vertices[v]);
      }
  std::vector<std::array<int, 3>> facets;
  facets.reserve(triangles.size());
  for (const auto& f : triangles) facets.push_back({index[f[0]], index[f[1]], index[f[2]]});
  char switches[96];
  std::snprintf(switches, sizeof switches, "pq1.5/12a%.9gQ", h_m * h_m * h_m / (6 * std::numbers::sqrt2));
  // A self-intersecting surface trips an assertion deep in the fill (TetGen 1.5 aborts there), so
  // TetGen's own intersection test runs first.
  TetgenFill fill = tetgen_fill(used, facets, switches, true);
  if (fill.intersecting_faces > 0)
    refuse("the surface intersects itself (" + std::to_string(fill.intersecting_faces) + " faces cross another)");
  if (fill.failure_code != 0) refuse(tetgen_failure(fill.failure_code));
  if (fill.mesh.tets.empty()) refuse("TetGen returned no tetrahedra");
  return std::move(fill.mesh);
}

Tet10Mesh quadratic_mesh(LinearMesh& m) {
  std::vector<int> vertex_node(m.points.size(), -1);
  std::vector<P3> nodes;
  std::unordered_map<std::int64_t, int> mid;
  auto vertex = [&](int v) {
    if (vertex_node[v] < 0) {
      vertex_node[v] = static_cast<int>(nodes.size());
      nodes.push_back(m.points[v]);
    }
    return vertex_node[v];
  };
  auto mid_node = [&](int a, int b) {
    const auto [it, inserted] =
        mid.try_emplace(edge_key(std::min(a, b), std::max(a, b)), static_cast<int>(nodes.size()));
    if (inserted)
      nodes.push_back({0.5 * (nodes[a][0] + nodes[b][0]), 0.5 * (nodes[a][1] + nodes[b][1]),
                       0.5 * (nodes[a][2] + nodes[b][2])});
    return it->second;
  };
  Tet10Mesh out;
  out.elements.reserve(m.tets.size());
  for (auto& t : m.tets) {
    const double o = orientation(m, t);
    if (!(o != 0)) refuse("TetGen made a degenerate tetrahedron");
    if (o < 0) std::swap(t[1], t[2]);
    std::array<int, kTet10Nodes> e{};
    for (int k = 0; k < 4; ++k) e[k] = vertex(t[k]);
    for (int k = 0; k < 6; ++k) e[4 + k] = mid_node(e[kTet10Edges[k][0]], e[kTet10Edges[k][1]]);
    out.elements.push_back(e);
  }
  out.nodes_m.resize(3, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t v = 0; v < nodes.size(); ++v)
    for (int k = 0; k < 3; ++k) out.nodes_m(k, static_cast<Eigen::Index>(v)) = nodes[v][k];
  return out;
}

}  // namespace

double enclosed_volume_m3(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  check_surface(vertices, triangles);  // indices in range before they index (and a closed surface, or no volume)
  double six_v = 0;
  for (const auto& f : triangles) {
    const P3 &a = vertices[f[0]], &b = vertices[f[1]], &c = vertices[f[2]];
    six_v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six_v / 6;
}

LinearMesh tetrahedralize_linear(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                                 double edge_length_m) {
  if (!(edge_length_m > 0) || !std::isfinite(edge_length_m))
    refuse("the edge length must be positive (" + std::to_string(edge_length_m) + " m)");
  check_surface(vertices, triangles);
  if (!(enclosed_volume_m3(vertices, triangles) > 0))
    refuse("the surface encloses no positive volume (triangles clockwise seen from outside?)");
  return run_tetgen(vertices, triangles, edge_length_m);
}

Tet10Mesh tetrahedralize_surface(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                                 double edge_length_m) {
  LinearMesh linear = tetrahedralize_linear(vertices, triangles, edge_length_m);
  return quadratic_mesh(linear);
}

}  // namespace clatter::kernels::fem
