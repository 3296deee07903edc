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
// Should TetGen still put a point on the surface, it lies on a flat facet and is moved here onto
// the smooth surface.
#include "kernels/fem/object_mesh.hpp"

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

std::int64_t edge_key(int a, int b) {
  return static_cast<std::int64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b));
}

LinearMesh run_tetgen(const RefinedSurface& s, const ObjectMeshSettings& settings, double h_m, std::vector<Face>& faces,
                      std::vector<int>& face_facet) {
  char switches[128];
  std::snprintf(switches, sizeof switches, "pYq%.6g/%.6ga%.9gQ", settings.max_radius_edge, settings.min_dihedral_deg,
                h_m * h_m * h_m / (6 * std::numbers::sqrt2));
  TetgenFill fill;
  try {
    fill = tetgen_fill(s.points_m, s.facets, switches, false, true);
  } catch (const std::invalid_argument& e) {
    throw MeshError("object mesh", e.what());
  }
  if (fill.failure_code != 0)
    throw MeshError("object mesh", "TetGen failed (code " + std::to_string(fill.failure_code) + ") with switches " + switches);
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

// Barycentric coordinates of x (on the plane of a, b, c, up to rounding), clamped into the triangle.
P3 barycentric(const P3& x, const P3& a, const P3& b, const P3& c) {
  double d00 = 0, d01 = 0, d11 = 0, d20 = 0, d21 = 0;
  for (int k = 0; k < 3; ++k) {
    const double v0 = b[k] - a[k], v1 = c[k] - a[k], v2 = x[k] - a[k];
    d00 += v0 * v0, d01 += v0 * v1, d11 += v1 * v1, d20 += v2 * v0, d21 += v2 * v1;
  }
  const double det = d00 * d11 - d01 * d01;
  P3 w{0, (d11 * d20 - d01 * d21) / det, (d00 * d21 - d01 * d20) / det};
  w[0] = 1 - w[1] - w[2];
  double sum = 0;
  for (double& x_k : w) sum += (x_k = std::max(x_k, 0.0));
  for (double& x_k : w) x_k /= sum;
  return w;
}

// A boundary face's place on the smooth surface: the input triangle it lies in and its three
// vertices' barycentric coordinates there.
struct FacePlace {
  int source;
  std::array<P3, 3> at;
};

FacePlace place_face(const Face& f, int facet, const RefinedSurface& s, const std::vector<P3>& flat) {
  FacePlace out{s.source[facet], {}};
  const Face& g = s.facets[facet];
  const auto& cb = s.corner_barycentric[facet];
  for (int i = 0; i < 3; ++i) {
    const int corner = g[0] == f[i] ? 0 : g[1] == f[i] ? 1 : g[2] == f[i] ? 2 : -1;
    const P3 w = corner >= 0 ? P3{corner == 0 ? 1.0 : 0.0, corner == 1 ? 1.0 : 0.0, corner == 2 ? 1.0 : 0.0}
                             : barycentric(flat[f[i]], s.points_m[g[0]], s.points_m[g[1]], s.points_m[g[2]]);
    for (int k = 0; k < 3; ++k) out.at[i][k] = w[0] * cb[0][k] + w[1] * cb[1][k] + w[2] * cb[2][k];
  }
  return out;
}

P3 midpoint(const P3& a, const P3& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}; }

ObjectMesh quadratic_mesh(LinearMesh& m, const RefinedSurface& s, const SmoothSurface& surface, const std::vector<Face>& faces,
                          const std::vector<int>& face_facet) {
  for (auto& t : m.tets) {
    const double o = orientation(m, t);
    if (!(o != 0)) throw MeshError("object mesh", "TetGen made a degenerate tetrahedron");
    if (o < 0) std::swap(t[1], t[2]);
  }
  std::map<Face, int> facet_of;
  for (std::size_t f = 0; f < faces.size(); ++f) facet_of.emplace(sorted(faces[f]), face_facet[f]);
  const std::vector<Face> boundary = boundary_faces(m);
  const std::vector<P3> flat = m.points;
  std::vector<P3> nodes = m.points;
  std::vector<FacePlace> places;
  std::vector<bool> placed(nodes.size(), false);
  for (const Face& f : boundary) {
    const auto it = facet_of.find(sorted(f));
    if (it == facet_of.end() || it->second < 0) throw MeshError("object mesh", "a boundary face TetGen did not mark");
    places.push_back(place_face(f, it->second, s, flat));
    for (int i = 0; i < 3; ++i)
      if (static_cast<std::size_t>(f[i]) >= s.points_m.size() && !placed[f[i]])  // a point TetGen added on the surface
        nodes[f[i]] = surface.point(places.back().source, places.back().at[i]), placed[f[i]] = true;
  }
  ObjectMesh out;
  std::unordered_map<std::int64_t, int> mid;  // numbered in order of first use: deterministic
  auto add_mid = [&](int a, int b, const P3& x) {
    const auto [it, fresh] = mid.try_emplace(edge_key(a, b), static_cast<int>(nodes.size()));
    if (fresh) nodes.push_back(x);
    return it->second;
  };
  // Boundary mid-nodes first, on the smooth surface at the edge's parameter midpoint.
  for (std::size_t b = 0; b < boundary.size(); ++b) {
    const Face& f = boundary[b];
    const FacePlace& p = places[b];
    BoundaryFace face{f[0], f[1], f[2], 0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], c = f[(k + 1) % 3];
      const bool fresh = !mid.count(edge_key(a, c));
      face[3 + k] = add_mid(a, c, surface.point(p.source, midpoint(p.at[k], p.at[(k + 1) % 3])));
      if (!fresh) continue;
      const P3 chord = midpoint(nodes[a], nodes[c]), &x = nodes[face[3 + k]];
      const double length = std::hypot(nodes[a][0] - nodes[c][0], nodes[a][1] - nodes[c][1], nodes[a][2] - nodes[c][2]);
      out.curved_edges += std::hypot(x[0] - chord[0], x[1] - chord[1], x[2] - chord[2]) > 1e-9 * length;
      for (int e = 0; e < 3; ++e)  // along input edge e: the input corner opposite it has weight 0 at both ends
        if (surface.sharp(p.source, e) && std::abs(p.at[k][(e + 2) % 3]) < 1e-9 && std::abs(p.at[(k + 1) % 3][(e + 2) % 3]) < 1e-9) {
          ++out.sharp_edges;
          break;
        }
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

}  // namespace

ObjectMesh mesh_object(const std::vector<P3>& vertices, const std::vector<Face>& triangles, const ObjectMeshSettings& settings,
                       const EllipsoidMeshBounds& bounds) {
  if (!(settings.edge_length_m > 0) || !std::isfinite(settings.edge_length_m) || settings.elements_through_thickness < 1 ||
      !(settings.smooth_dihedral_deg >= 0) || settings.retries < 0)
    throw std::invalid_argument("mesh_object: need edge length > 0, elements through thickness >= 1, smooth angle >= 0, retries >= 0");
  check_object_surface(vertices, triangles);
  const SmoothSurface surface(vertices, triangles, settings.smooth_dihedral_deg);
  const std::vector<double> thickness = thickness_under_triangles_m(vertices, triangles);
  // A vertex is as thin as the thinnest triangle around it: a plate's rim takes its faces' thickness.
  std::vector<double> vertex_thickness(vertices.size(), std::numeric_limits<double>::infinity());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles[t]) vertex_thickness[v] = std::min(vertex_thickness[v], thickness[t]);
  const double min_thickness = *std::min_element(thickness.begin(), thickness.end());
  std::string reasons;
  double scale = 1;  // a retry scales every size, the thickness's too
  for (int attempt = 0; attempt <= settings.retries; ++attempt, scale *= 0.8) {
    const double h = scale * settings.edge_length_m;
    std::vector<double> size(vertices.size());
    for (std::size_t v = 0; v < vertices.size(); ++v)
      size[v] = scale * std::min(settings.edge_length_m, vertex_thickness[v] / settings.elements_through_thickness);
    const RefinedSurface refined = refine_surface(vertices, triangles, surface, size, settings.max_surface_triangles);
    std::vector<Face> faces;
    std::vector<int> face_facet;
    LinearMesh linear = run_tetgen(refined, settings, h, faces, face_facet);
    ObjectMesh out = quadratic_mesh(linear, refined, surface, faces, face_facet);
    out.quality = mesh_quality(out.mesh);
    out.quality.edge_length_m = scale * std::min(settings.edge_length_m, min_thickness / settings.elements_through_thickness);
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
