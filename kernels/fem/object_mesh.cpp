// The object mesher: TetGen's part and the mid-nodes (object_mesh.hpp has the steps).
//
// TetGen switches, "pYq<r>/<d>a<v>Q" (the ellipsoid mesher's):
//   p   the input is a piecewise linear complex (the refined surface, one facet per triangle, each
//       marked with its index so a boundary face TetGen writes names the facet it lies in);
//   Y   keep the surface as refined here: its points are on the smooth surface already. Without
//       -Y TetGen splits the facets' edges (every one a segment to it) into short pieces near
//       the surface and leaves tetrahedra of radius-edge ratio 5.8 and dihedral angles of 2
//       degrees on a sphere (1559 of 21658 outside the bounds); with it, 1.7 and 7 degrees, none;
//   q   quality: radius-edge ratio <= r, dihedral angles >= d degrees;
//   a   volume bound v = h^3 / (6 sqrt 2), the regular tetrahedron of edge h;
//   Q   quiet.
// Should TetGen still put a point on the surface, it lies on a flat facet and is projected here onto
// the smooth surface, as every boundary mid-node is.
#include "kernels/fem/object_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <unordered_map>

#include "kernels/fem/mesh_check.hpp"
#include "kernels/fem/object_parts.hpp"
#include "kernels/fem/smooth_surface.hpp"
#include "kernels/fem/tetgen_fill.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;
using Face = std::array<int, 3>;

LinearMesh run_tetgen(const RefinedSurface& s, const std::vector<P3>& inner, const ObjectMeshSettings& settings,
                      double h_m, std::vector<Face>& faces, std::vector<int>& face_facet) {
  std::vector<P3> points = s.points_m;
  points.insert(points.end(), inner.begin(), inner.end());
  char switches[128];
  std::snprintf(switches, sizeof switches, "pYq%.6g/%.6ga%.9gQ", settings.max_radius_edge, settings.min_dihedral_deg,
                h_m * h_m * h_m / (6 * std::numbers::sqrt2));
  TetgenFill fill;
  try {
    // No crossing test first (TetGen's takes 4 times the fill: 16 s on a 65,000-facet disk): the
    // refinement's moves keep every star unfolded, so the refined surface crosses itself only
    // where the input does, which check_object_surface refused.
    fill = tetgen_fill(points, s.facets, switches, false, true, s.holes_m);
  } catch (const std::invalid_argument& e) {
    throw MeshError("object mesh", e.what());
  }
  if (fill.failure_code != 0)
    throw MeshError("object mesh",
                    "TetGen failed (code " + std::to_string(fill.failure_code) + ") with switches " + switches);
  if (fill.mesh.tets.empty()) throw MeshError("object mesh", "TetGen returned no tetrahedra");
  if (fill.face_facet.size() != fill.faces.size()) throw MeshError("object mesh", "TetGen wrote no facet markers");
  for (std::size_t v = 0; v < s.points_m.size(); ++v)
    if (fill.mesh.points[v] != s.points_m[v]) throw MeshError("object mesh", "TetGen moved a surface point");
  faces = std::move(fill.faces);
  face_facet = std::move(fill.face_facet);
  return std::move(fill.mesh);
}

Face sorted(Face f) {
  std::sort(f.begin(), f.end());
  return f;
}

// The faces met once, outward (against the opposite vertex; the tetrahedra are positive).
std::vector<Face> boundary_faces(const LinearMesh& m) {
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<Face, std::pair<int, Face>> count;  // ordered: the boundary comes out in a fixed order
  for (const auto& t : m.tets)
    for (const auto& face : kFaces) {
      const Face f{t[face[0]], t[face[1]], t[face[2]]};
      auto [it, fresh] = count.try_emplace(sorted(f), 0, f);
      ++it->second.first;
    }
  std::vector<Face> boundary;
  for (const auto& [key, entry] : count)
    if (entry.first == 1) boundary.push_back(entry.second);
  return boundary;
}

P3 midpoint(const P3& a, const P3& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}; }

ObjectMesh quadratic_mesh(LinearMesh& m, const RefinedSurface& s, const SurfaceProjector& projector,
                          const std::vector<Face>& faces, const std::vector<int>& face_facet) {
  for (auto& t : m.tets) {
    const double o = orientation(m, t);
    if (!(o != 0)) throw MeshError("object mesh", "TetGen made a degenerate tetrahedron");
    if (o < 0) std::swap(t[1], t[2]);
  }
  std::map<Face, int> facet_of;
  for (std::size_t f = 0; f < faces.size(); ++f) facet_of.emplace(sorted(faces[f]), face_facet[f]);
  const std::vector<Face> boundary = boundary_faces(m);
  std::vector<P3> nodes = m.points;
  std::vector<int> near;  // per boundary face: an input triangle near it
  for (const Face& f : boundary) {
    const auto it = facet_of.find(sorted(f));
    if (it == facet_of.end() || it->second < 0) throw MeshError("object mesh", "a boundary face TetGen did not mark");
    near.push_back(s.near_triangle[it->second]);
    for (int v : f)  // a point TetGen added on the surface (-Y allows none, but should it): onto it
      if (static_cast<std::size_t>(v) >= s.points_m.size() && nodes[v] == m.points[v])
        nodes[v] = projector.project(nodes[v], near.back());
  }
  ObjectMesh out;
  std::unordered_map<std::int64_t, int> mid;  // numbered in order of first use: deterministic
  auto add_mid = [&](int a, int b, const P3& x) {
    const auto [it, fresh] = mid.try_emplace(undirected_edge_key(a, b), static_cast<int>(nodes.size()));
    if (fresh) nodes.push_back(x);
    return it->second;
  };
  // Boundary mid-nodes first: the chord's midpoint projected onto the smooth surface.
  for (std::size_t b = 0; b < boundary.size(); ++b) {
    const Face& f = boundary[b];
    BoundaryFace face{f[0], f[1], f[2], 0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], c = f[(k + 1) % 3];
      if (mid.count(undirected_edge_key(a, c))) {
        face[3 + k] = mid.at(undirected_edge_key(a, c));
        continue;
      }
      const P3 chord = midpoint(nodes[a], nodes[c]);
      int start = near[b];
      face[3 + k] = add_mid(a, c, projector.project(chord, start));
      const P3& x = nodes[face[3 + k]];
      const double length = std::hypot(nodes[a][0] - nodes[c][0], nodes[a][1] - nodes[c][1], nodes[a][2] - nodes[c][2]);
      out.curved_edges += std::hypot(x[0] - chord[0], x[1] - chord[1], x[2] - chord[2]) > 1e-9 * length;
      out.sharp_edges += s.sharp_edges.count(undirected_edge_key(a, c)) > 0;
    }
    out.boundary.push_back(face);
  }
  for (const auto& t : m.tets) {
    std::array<int, kTet10Nodes> e{t[0], t[1], t[2], t[3]};
    for (int k = 0; k < 6; ++k) {
      const int a = t[kTet10Edges[k][0]], b = t[kTet10Edges[k][1]];
      e[4 + k] = add_mid(a, b, midpoint(nodes[a], nodes[b]));
    }
    out.mesh.elements.push_back(e);
  }
  out.mesh.nodes_m.resize(3, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t v = 0; v < nodes.size(); ++v)
    for (int k = 0; k < 3; ++k) out.mesh.nodes_m(k, static_cast<Eigen::Index>(v)) = nodes[v][k];
  return out;
}

std::string bounds_problem(const MeshQuality& q, const EllipsoidMeshBounds& b) {
  char reason[160] = "";
  if (!(q.min_jacobian_ratio > 0))
    std::snprintf(reason, sizeof reason, "an element folds (det J <= 0, ratio %.3g)", q.min_jacobian_ratio);
  else if (!(q.min_jacobian_ratio >= b.min_jacobian_ratio))
    std::snprintf(reason, sizeof reason, "Jacobian ratio %.3g below %.3g", q.min_jacobian_ratio, b.min_jacobian_ratio);
  else if (q.max_radius_edge > b.max_radius_edge)
    std::snprintf(reason, sizeof reason, "radius-edge ratio %.3g above %.3g", q.max_radius_edge, b.max_radius_edge);
  else if (q.min_dihedral_deg < b.min_dihedral_deg)
    std::snprintf(reason, sizeof reason, "dihedral angle %.3g deg below %.3g", q.min_dihedral_deg, b.min_dihedral_deg);
  return reason;
}

// Points under the curved elements that break the Jacobian bound: most are caps, tetrahedra on
// four surface points with two faces on the surface (TetGen, kept from splitting the surface,
// leaves some where no interior point is near); curving both faces outward folds them. A point
// under the cap lies inside its circumsphere (about the surface's osculating sphere), so TetGen's
// Delaunay fill replaces the cap. Each goes below the centroid by 0.3 of the faces' mean edge.
std::vector<P3> points_under_folds(const ObjectMesh& out, const EllipsoidMeshBounds& bounds) {
  std::map<Face, int> on_boundary;
  for (std::size_t b = 0; b < out.boundary.size(); ++b)
    on_boundary.emplace(sorted({out.boundary[b][0], out.boundary[b][1], out.boundary[b][2]}), static_cast<int>(b));
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::vector<P3> points;
  for (const auto& e : out.mesh.elements) {
    Tet10Coords x;
    for (int i = 0; i < kTet10Nodes; ++i) x.col(i) = out.mesh.nodes_m.col(e[i]);
    if (jacobian_ratio(x) >= bounds.min_jacobian_ratio) continue;
    Eigen::Vector3d outward = Eigen::Vector3d::Zero();
    double edges = 0;
    int faces = 0;
    for (const auto& face : kFaces) {
      if (!on_boundary.count(sorted({e[face[0]], e[face[1]], e[face[2]]}))) continue;
      const Eigen::Vector3d a = x.col(face[0]), b = x.col(face[1]), c = x.col(face[2]);
      outward += (b - a).cross(c - a).normalized();
      edges += (b - a).norm() + (c - b).norm() + (a - c).norm();
      ++faces;
    }
    if (faces == 0) continue;
    const Eigen::Vector3d p = x.leftCols<4>().rowwise().mean() - 0.3 * edges / (3 * faces) * outward.normalized();
    points.push_back({p(0), p(1), p(2)});
  }
  return points;
}

// TetGen's fill of the refined surface and the quadratic mesh on it, with points added under
// folded elements for a few rounds (the mesh of the last round is returned either way).
ObjectMesh mesh_refined(const RefinedSurface& refined, const SurfaceProjector& projector,
                        const ObjectMeshSettings& settings, double h_m, const EllipsoidMeshBounds& bounds) {
  std::vector<P3> inner;
  for (int round = 0;; ++round) {
    std::vector<Face> faces;
    std::vector<int> face_facet;
    LinearMesh linear = run_tetgen(refined, inner, settings, h_m, faces, face_facet);
    ObjectMesh out = quadratic_mesh(linear, refined, projector, faces, face_facet);
    out.quality = mesh_quality(out.mesh);
    if (round == 4 || out.quality.min_jacobian_ratio >= bounds.min_jacobian_ratio) return out;
    const std::vector<P3> more = points_under_folds(out, bounds);
    if (more.empty()) return out;
    inner.insert(inner.end(), more.begin(), more.end());
  }
}

}  // namespace

ObjectMesh mesh_object(const std::vector<P3>& vertices, const std::vector<Face>& triangles,
                       const ObjectMeshSettings& settings, const EllipsoidMeshBounds& bounds) {
  if (!(settings.edge_length_m > 0) || !std::isfinite(settings.edge_length_m) ||
      settings.elements_through_thickness < 1 || !(settings.smooth_dihedral_deg >= 0) || settings.retries < 0)
    throw std::invalid_argument(
        "mesh_object: need edge length > 0, elements through thickness >= 1, smooth angle >= 0, retries >= 0");
  check_object_surface(vertices, triangles);
  const SmoothSurface surface(vertices, triangles, settings.smooth_dihedral_deg);
  const SurfaceProjector projector(vertices, triangles, surface);
  const std::vector<double> thickness = thickness_under_triangles_m(vertices, triangles);
  // A vertex is as thin as the thinnest triangle around it: a plate's rim takes its faces' thickness.
  std::vector<double> vertex_thickness(vertices.size(), std::numeric_limits<double>::infinity());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles[t]) vertex_thickness[v] = std::min(vertex_thickness[v], thickness[t]);
  const double min_thickness = *std::min_element(thickness.begin(), thickness.end());
  const std::vector<P3> holes = points_in_cavities_m(vertices, triangles, cavity_triangles(vertices, triangles));
  std::string reasons;
  double scale = 1;  // a retry scales every size, the thickness's too
  for (int attempt = 0; attempt <= settings.retries; ++attempt, scale *= 0.8) {
    std::vector<double> size(vertices.size());
    for (std::size_t v = 0; v < vertices.size(); ++v)
      size[v] = scale * std::min(settings.edge_length_m, vertex_thickness[v] / settings.elements_through_thickness);
    RefinedSurface refined = refine_surface(vertices, triangles, projector, size, settings.max_surface_triangles);
    refined.holes_m = holes;
    ObjectMesh out = mesh_refined(refined, projector, settings, scale * settings.edge_length_m, bounds);
    out.quality.edge_length_m =
        scale * std::min(settings.edge_length_m, min_thickness / settings.elements_through_thickness);
    out.min_thickness_m = min_thickness;
    const std::string problem = bounds_problem(out.quality, bounds);
    if (problem.empty()) return out;
    char tried[64];
    std::snprintf(tried, sizeof tried, "%sh %.4g m: ", reasons.empty() ? "" : "; ", out.quality.edge_length_m);
    reasons += tried + problem;
  }
  throw MeshError("object mesh", "no mesh within the quality bounds (" + reasons + ")");
}

}  // namespace clatter::kernels::fem
