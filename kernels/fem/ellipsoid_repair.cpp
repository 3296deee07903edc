// Interior points handed to TetGen with the surface, and the repairs of a mesh that breaks the
// bounds (no TetGen here).
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <unordered_map>
#include <vector>

#include "kernels/fem/ellipsoid_parts.hpp"
#include "kernels/fem/mesh_quality.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

// The layer's depth under a vertex, in mean edges there. Deeper, the tetrahedra between surface
// and layer are less flat and fewer (measured, 0.5 / 0.65 / 0.8: the 1:20:20 pancake at h 0.1
// 450k / 393k / 353k dofs, and 0.5 leaves 1:1:20 folded), but the sphere gets coarser too (h 0.35:
// 8496 / 7836 / 6945 dofs, worst Lamb error 0.50 / 0.55 / 0.64 %; at h 0.25 0.145 / 0.164 / 0.191 %
// against the 0.2 % that tests/mpi/test_modal_sphere.cpp asks). The caps a layer misses are
// repaired (repair_mesh).
constexpr double kLayerDepth = 0.65;
constexpr std::size_t kMaxRepairs = 64;

P3 inward_normal(const P3& r, const P3& x) {
  const P3 g{x[0] / (r[0] * r[0]), x[1] / (r[1] * r[1]), x[2] / (r[2] * r[2])};
  const double norm = std::hypot(g[0], g[1], g[2]);
  return {-g[0] / norm, -g[1] / norm, -g[2] / norm};
}

P3 below(const P3& r, const P3& x, double depth) {
  const P3 n = inward_normal(r, x);
  return {x[0] + depth * n[0], x[1] + depth * n[1], x[2] + depth * n[2]};
}

// A cap on two boundary faces: TetGen made it to recover them and would again; the other diagonal
// of their quadrilateral on the surface takes it out of the domain.
bool flip_under_cap(const std::array<int, kTet10Nodes>& e, const std::set<std::array<int, 3>>& boundary,
                    SurfaceTriangulation& surface) {
  std::vector<int> on_boundary;  // the vertex opposite each boundary face of the element
  for (int i = 0; i < 4; ++i) {
    std::array<int, 3> t{e[(i + 1) % 4], e[(i + 2) % 4], e[(i + 3) % 4]};
    std::sort(t.begin(), t.end());
    if (boundary.count(t)) on_boundary.push_back(i);
  }
  if (on_boundary.size() != 2) return false;
  int shared[2], n = 0;
  for (int i = 0; i < 4; ++i)
    if (i != on_boundary[0] && i != on_boundary[1]) shared[n++] = e[i];
  return flip_surface_edge(surface, shared[0], shared[1]);
}

// Below the centroid of a folded element's surface vertices (of all four if none), half its
// mean edge deep.
P3 point_under(const Tet10Coords& x, const std::array<int, kTet10Nodes>& e, std::size_t n_surface, const P3& r) {
  P3 c{0, 0, 0};
  int count = 0;
  for (int pass = 0; pass < 2 && count == 0; ++pass)
    for (int i = 0; i < 4; ++i)
      if (pass == 1 || static_cast<std::size_t>(e[i]) < n_surface) {
        ++count;
        for (int k = 0; k < 3; ++k) c[k] += x(k, i);
      }
  double edges = 0;
  for (const auto& edge : kTet10Edges) edges += (x.col(edge[0]) - x.col(edge[1])).norm();
  const P3 p = nearest_on_ellipsoid(r, {c[0] / count, c[1] / count, c[2] / count});
  return below(r, p, std::min(0.5 * edges / 6, 0.5 * normal_chord_m(r, p)));
}

}  // namespace

// One point under each surface vertex, half its mean edge length deep along the inward normal (at
// most half the chord through the body there: the thin rim), skipped where it would come closer
// than that to one already placed (near a sharp tip, or the two sides of a rim).
// Without them TetGen, which may not split the preserved surface (-Y), leaves "caps": tetrahedra
// on four surface vertices, only a sagitta thick, which fold once their mid-nodes are curved. A
// point under a cap lies inside its circumsphere (about the osculating sphere) where the surface's
// curvature radius exceeds the depth, so Delaunay insertion removes the cap there; the few caps
// whose sphere is shallower are repaired after TetGen (repair_mesh).
std::vector<P3> inner_layer(const SurfaceTriangulation& surface, const P3& r) {
  std::vector<double> edge_sum(surface.vertices_m.size(), 0);
  std::vector<int> edge_count(surface.vertices_m.size(), 0);
  for (const auto& f : surface.faces)
    for (int k = 0; k < 3; ++k) {
      const P3 &a = surface.vertices_m[f[k]], &b = surface.vertices_m[f[(k + 1) % 3]];
      const double len = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      edge_sum[f[k]] += len;
      ++edge_count[f[k]];
    }
  double min_depth = std::numeric_limits<double>::infinity();
  for (std::size_t v = 0; v < edge_sum.size(); ++v) min_depth = std::min(min_depth, 0.5 * edge_sum[v] / edge_count[v]);
  // The crowding test against one grid per octave of depth, of cells as wide as its deepest
  // point, so a graded surface needs only the 27 cells around each point per octave.
  std::vector<std::unordered_map<long long, std::vector<int>>> grids;
  auto cell = [](const P3& p, double width, int dx, int dy, int dz) {
    const auto c = [&](int k, int d) { return (static_cast<long long>(std::floor(p[k] / width)) + d) & 0x1fffff; };
    return c(0, dx) << 42 | c(1, dy) << 21 | c(2, dz);
  };
  std::vector<P3> layer;
  std::vector<double> spacing;
  for (std::size_t v = 0; v < surface.vertices_m.size(); ++v) {
    const P3& x = surface.vertices_m[v];
    const double depth = std::min(kLayerDepth * edge_sum[v] / edge_count[v], 0.5 * normal_chord_m(r, x));
    const P3 p = below(r, x, depth);
    bool crowded = false;
    for (std::size_t level = 0; level < grids.size() && !crowded; ++level) {
      const double width = min_depth * std::ldexp(1.0, static_cast<int>(level) + 1);
      for (int d = 0; d < 27 && !crowded; ++d) {
        const auto it = grids[level].find(cell(p, width, d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1));
        if (it == grids[level].end()) continue;
        for (int q : it->second)
          crowded = crowded || std::hypot(p[0] - layer[q][0], p[1] - layer[q][1], p[2] - layer[q][2]) < std::min(depth, spacing[q]);
      }
    }
    if (!crowded) {
      std::size_t level = 0;
      while (depth >= min_depth * std::ldexp(1.0, static_cast<int>(level) + 1)) ++level;
      if (grids.size() <= level) grids.resize(level + 1);
      grids[level][cell(p, min_depth * std::ldexp(1.0, static_cast<int>(level) + 1), 0, 0, 0)].push_back(static_cast<int>(layer.size()));
      layer.push_back(p);
      spacing.push_back(depth);
    }
  }
  return layer;
}

bool repair_mesh(const EllipsoidMesh& m, const EdgeRule& rule, const EllipsoidMeshBounds& bounds,
                 const std::vector<P3>& inner, SurfaceTriangulation& surface, MeshRepairs& repairs) {
  const std::size_t n_surface = surface.vertices_m.size();
  std::set<std::array<int, 3>> boundary;
  std::set<std::array<int, 2>> surface_edges;
  for (const auto& f : m.boundary) {
    std::array<int, 3> t{f[0], f[1], f[2]};
    std::sort(t.begin(), t.end());
    boundary.insert(t);
    for (int k = 0; k < 3; ++k) surface_edges.insert({std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])});
  }
  std::vector<std::size_t> bad;
  for (std::size_t i = 0; i < m.mesh.elements.size(); ++i) {
    Tet10Coords x;
    for (int k = 0; k < kTet10Nodes; ++k) x.col(k) = m.mesh.nodes_m.col(m.mesh.elements[i][k]);
    const ElementQuality q = element_quality(x);
    if (!(q.jacobian_ratio >= bounds.min_jacobian_ratio && q.radius_edge <= bounds.max_radius_edge &&
          q.min_dihedral_deg >= bounds.min_dihedral_deg))
      bad.push_back(i);
  }
  // Repairs mend local defects; bounds that a sizeable share of the elements break are out of
  // this mesh's reach (and repairing them all would refine it without end).
  if (bad.size() > std::max<std::size_t>(kMaxRepairs, m.mesh.elements.size() / 10)) return false;
  bool changed = false;
  std::vector<std::array<int, 2>> to_bisect;
  for (std::size_t i : bad) {
    const auto& e = m.mesh.elements[i];
    Tet10Coords x;
    for (int k = 0; k < kTet10Nodes; ++k) x.col(k) = m.mesh.nodes_m.col(e[k]);
    const bool folded = !(jacobian_ratio(x) >= bounds.min_jacobian_ratio);
    if (folded && flip_under_cap(e, boundary, surface)) {
      changed = true;
      continue;
    }
    // Badly shaped: TetGen cannot mend an element it may not cut the surface under (-Y). Its
    // longest surface edge cut in two gives it room; without one, the later of two of our
    // points at its shortest edge goes (they crowd it).
    std::array<int, 2> longest_surface{-1, -1}, shortest{-1, -1};
    double longest_m = 0, shortest_m = std::numeric_limits<double>::infinity();
    for (const auto& edge : kTet10Edges) {
      const std::array<int, 2> ab{std::min(e[edge[0]], e[edge[1]]), std::max(e[edge[0]], e[edge[1]])};
      const double length = (x.col(edge[0]) - x.col(edge[1])).norm();
      if (surface_edges.count(ab) && length > longest_m) longest_m = length, longest_surface = ab;
      if (length < shortest_m) shortest_m = length, shortest = ab;
    }
    if (!folded) {
      if (longest_surface[0] >= 0) {
        to_bisect.push_back(longest_surface);
      } else {
        const auto ours = [&](int v) { return v >= static_cast<int>(n_surface) && v < static_cast<int>(n_surface + inner.size()); };
        const int v = ours(shortest[1]) ? shortest[1] : ours(shortest[0]) ? shortest[0] : -1;
        if (v >= 0) changed = repairs.dropped.insert(inner[v - n_surface]).second || changed;
      }
      continue;
    }
    repairs.extra.push_back(point_under(x, e, n_surface, rule.semi_axes_m));
    changed = true;
  }
  if (!to_bisect.empty()) bisect_surface_edges(surface, rule, to_bisect);
  return changed || !to_bisect.empty();
}

}  // namespace clatter::kernels::fem
