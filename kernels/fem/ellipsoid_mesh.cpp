// TetGen's part of the ellipsoid mesher (the only file that sees TetGen), the mid-nodes and the
// quality statistics.
//
// TetGen switches, "pYQq<r>/<d>a<v>":
//   p   the input is a piecewise linear complex (our closed surface triangulation);
//   Y   keep that surface as it is: no Steiner point on the boundary, so every boundary vertex is
//       one of ours, on the ellipsoid, and the boundary mid-nodes can be put on the surface;
//   Q   quiet: nothing on stdout (a library prints no progress into a bank job's log);
//   q   quality refinement: radius-edge ratio <= r and smallest dihedral angle >= d degrees;
//   a   volume bound v = h^3 / (6 sqrt 2), the regular tetrahedron of edge h: the interior is h,
//       and -q grades it from the curvature-refined surface to h (each point it inserts is a bad
//       tetrahedron's circumcentre, so sizes grow away from the surface no faster than the
//       radius-edge bound allows); no size function is needed.
// No -o2: TetGen's second-order nodes sit at straight midpoints; the curved ones are made here.
#include "kernels/fem/ellipsoid_mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "kernels/fem/ellipsoid_parts.hpp"
#include "kernels/fem/mesh_quality.hpp"
#include "kernels/fem/tetgen_fill.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

constexpr int kRepairRounds = 6;

LinearMesh run_tetgen(const SurfaceTriangulation& surface, const std::vector<P3>& inner, const EllipsoidMeshSettings& s,
                      double h) {
  std::vector<P3> points = surface.vertices_m;
  points.insert(points.end(), inner.begin(), inner.end());
  char switches[128];
  std::snprintf(switches, sizeof switches, "pYQq%.6g/%.6ga%.9g", s.max_radius_edge, s.min_dihedral_deg,
                h * h * h / (6 * std::numbers::sqrt2));
  TetgenFill fill;
  try {
    fill = tetgen_fill(points, surface.faces, switches);
  } catch (const std::invalid_argument& e) {
    throw MeshError(e.what());
  }
  if (fill.failure_code != 0)
    throw MeshError("TetGen failed (code " + std::to_string(fill.failure_code) + ") with switches " + switches);
  if (fill.mesh.tets.empty()) throw MeshError("TetGen returned no tetrahedra");
  return std::move(fill.mesh);
}

long long edge_key(int a, int b) { return static_cast<long long>(std::min(a, b)) << 32 | std::max(a, b); }

// The faces met once: the boundary, oriented outward (against the opposite vertex), with their
// vertices checked to be input points (on the ellipsoid).
std::vector<std::array<int, 3>> boundary_faces(const LinearMesh& m, std::size_t n_surface_points) {
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};  // outward for det > 0
  std::unordered_map<std::string, int> count;
  std::vector<std::array<int, 3>> candidates;
  auto key = [](std::array<int, 3> f) {
    std::sort(f.begin(), f.end());
    return std::to_string(f[0]) + ',' + std::to_string(f[1]) + ',' + std::to_string(f[2]);
  };
  for (const auto& t : m.tets)
    for (const auto& face : kFaces) {
      const std::array<int, 3> f{t[face[0]], t[face[1]], t[face[2]]};
      if (count[key(f)]++ == 0) candidates.push_back(f);
    }
  std::vector<std::array<int, 3>> boundary;
  for (const auto& f : candidates)
    if (count[key(f)] == 1) {
      for (int v : f)
        if (static_cast<std::size_t>(v) >= n_surface_points) throw MeshError("a boundary face has a vertex off the surface (a Steiner point of TetGen's)");
      boundary.push_back(f);
    }
  return boundary;
}

}  // namespace

EllipsoidMesh quadratic_mesh(LinearMesh& m, const P3& r, std::size_t n_surface_points) {
  return quadratic_mesh(m, n_surface_points, [&](int a, int b, bool on_surface) {
    const P3 c{0.5 * (m.points[a][0] + m.points[b][0]), 0.5 * (m.points[a][1] + m.points[b][1]),
               0.5 * (m.points[a][2] + m.points[b][2])};
    return on_surface ? nearest_on_ellipsoid(r, c) : c;
  });
}

EllipsoidMesh quadratic_mesh(LinearMesh& m, std::size_t n_surface_points, const MidNodePlacement& place) {
  for (auto& t : m.tets)
    if (orientation(m, t) < 0) std::swap(t[1], t[2]);
  const auto boundary = boundary_faces(m, n_surface_points);
  std::unordered_map<long long, bool> on_surface;
  for (const auto& f : boundary)
    for (int k = 0; k < 3; ++k) on_surface[edge_key(f[k], f[(k + 1) % 3])] = true;
  std::vector<P3> nodes = m.points;
  std::unordered_map<long long, int> mid;  // numbered in order of first use: deterministic
  auto mid_node = [&](int a, int b) {
    const auto [it, inserted] = mid.try_emplace(edge_key(a, b), static_cast<int>(nodes.size()));
    if (inserted) nodes.push_back(place(a, b, on_surface.count(edge_key(a, b)) > 0));
    return it->second;
  };
  EllipsoidMesh out;
  for (const auto& t : m.tets) {
    std::array<int, kTet10Nodes> e{t[0], t[1], t[2], t[3]};
    for (int k = 0; k < 6; ++k) e[4 + k] = mid_node(t[kTet10Edges[k][0]], t[kTet10Edges[k][1]]);
    out.mesh.elements.push_back(e);
  }
  for (const auto& f : boundary)
    out.boundary.push_back({f[0], f[1], f[2], mid_node(f[0], f[1]), mid_node(f[1], f[2]), mid_node(f[2], f[0])});
  out.mesh.nodes_m.resize(3, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t v = 0; v < nodes.size(); ++v)
    for (int k = 0; k < 3; ++k) out.mesh.nodes_m(k, static_cast<Eigen::Index>(v)) = nodes[v][k];
  return out;
}

void check_bounds(const MeshQuality& q, const EllipsoidMeshBounds& b) {
  char reason[256] = "";
  if (!(q.min_jacobian_ratio > 0) && !(q.min_jacobian_ratio >= b.min_jacobian_ratio))
    std::snprintf(reason, sizeof reason, "a curved element has det J <= 0 (ratio %.3g)", q.min_jacobian_ratio);
  else if (!(q.min_jacobian_ratio >= b.min_jacobian_ratio))
    std::snprintf(reason, sizeof reason, "Jacobian ratio %.3g below %.3g", q.min_jacobian_ratio, b.min_jacobian_ratio);
  else if (q.max_radius_edge > b.max_radius_edge)
    std::snprintf(reason, sizeof reason, "radius-edge ratio %.3g above %.3g", q.max_radius_edge, b.max_radius_edge);
  else if (q.min_dihedral_deg < b.min_dihedral_deg)
    std::snprintf(reason, sizeof reason, "dihedral angle %.3g deg below %.3g", q.min_dihedral_deg, b.min_dihedral_deg);
  if (reason[0] != '\0') throw MeshError(reason);
}

EllipsoidMesh mesh_ellipsoid(const EllipsoidMeshSettings& s, const EllipsoidMeshBounds& bounds) {
  const P3& r = s.semi_axes_m;
  if (!(r[0] > 0 && r[1] > 0 && r[2] > 0 && s.edge_length_m > 0 && s.elements_through_thickness > 0))
    throw std::invalid_argument("mesh_ellipsoid: semi-axes, edge length and elements through the thickness must be positive");
  const double h = std::min(s.edge_length_m, 2 * std::min({r[0], r[1], r[2]}) / s.elements_through_thickness);
  SurfaceTriangulation surface = ellipsoid_surface(r, h, s.spacing_per_curvature_radius);
  const EdgeRule rule = surface_rule(r, h, s.spacing_per_curvature_radius);
  MeshRepairs repairs;
  EllipsoidMesh out;
  // An element that breaks the bounds (a fold: a cap the layer missed, or one TetGen made to
  // recover the surface; a bad shape TetGen could not mend without cutting the surface) is
  // repaired and TetGen runs again: a few rounds; most meshes need none, and a mesh still bad
  // after them is refused below.
  for (int round = 0;; ++round) {
    std::vector<P3> inner;
    for (const P3& p : inner_layer(surface, r))
      if (!repairs.dropped.count(p)) inner.push_back(p);
    for (const P3& p : repairs.extra)
      if (!repairs.dropped.count(p)) inner.push_back(p);
    // A repair's surface bisections can make faces cross where the body is thinner than them
    // (TetGen 1.5 then fails, and its failure path frees its memory twice): keep the last mesh,
    // which the bounds judge below.
    if (round > 0 && tetgen_fill(surface.vertices_m, surface.faces, "", true).intersecting_faces > 0) break;
    LinearMesh linear = run_tetgen(surface, inner, s, h);
    for (std::size_t v = 0; v < surface.vertices_m.size(); ++v)
      if (linear.points[v] != surface.vertices_m[v]) throw MeshError("TetGen moved a surface point");
    out = quadratic_mesh(linear, r, surface.vertices_m.size());
    if (round == kRepairRounds || !repair_mesh(out, rule, bounds, inner, surface, repairs)) break;
  }
  out.quality = mesh_quality(out.mesh);
  out.quality.edge_length_m = h;
  check_bounds(out.quality, bounds);
  return out;
}

}  // namespace clatter::kernels::fem
