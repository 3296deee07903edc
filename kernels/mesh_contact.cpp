#include "kernels/mesh_contact.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace clatter::kernels {
namespace {

double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

// The point of triangle (a, b, c) nearest p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return add(a, scale(ab, d1 / (d1 - d3)));
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return add(a, scale(ac, d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double denom = 1 / (va + vb + vc);
  return add(a, add(scale(ab, vb * denom), scale(ac, vc * denom)));
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = sub(b, a);
  const double len2 = dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(dot(sub(p, a), ab) / len2, 0.0, 1.0) : 0.0;
  return norm(sub(p, add(a, scale(ab, t))));
}

double angle_between(const Vec3& u, const Vec3& v) {
  return std::atan2(norm(cross(u, v)), dot(u, v));  // accurate at small angles, unlike acos
}

}  // namespace

const char* to_string(ContactFeature f) {
  switch (f) {
    case ContactFeature::smooth: return "smooth";
    case ContactFeature::edge: return "edge";
    case ContactFeature::corner: return "corner";
  }
  return "?";
}

MeshContactRule mesh_contact_rule(const ProxyFit& proxy, double volume_m3, const std::vector<Vec3>& vertices_m,
                                  const Vec3& centroid_m) {
  if (!(volume_m3 > 0)) throw std::invalid_argument("mesh_contact_rule: volume must be > 0");
  MeshContactRule rule;
  rule.rounding_radius_m = 0.02 * std::cbrt(3 * volume_m3 / (4 * std::numbers::pi));
  rule.flat_radius_m = std::max(proxy.a_m * proxy.b_m / proxy.c_m, rule.rounding_radius_m);
  double reach = 0;
  for (const auto& v : vertices_m) reach = std::max(reach, norm(sub(v, centroid_m)));
  rule.max_offset_m = 0.5 * reach;
  return rule;
}

MeshContact::MeshContact(std::vector<Vec3> vertices_m, std::vector<std::array<int, 3>> triangles, const MeshContactRule& rule)
    : vertices_(std::move(vertices_m)), triangles_(std::move(triangles)), rule_(rule) {
  if (!(rule_.rounding_radius_m > 0) || !(rule_.flat_radius_m >= rule_.rounding_radius_m) || !(rule_.fit_edges > 0) ||
      !(rule_.sharp_angle_rad > 0) || !(rule_.max_offset_m > 0))
    throw std::invalid_argument("MeshContact: need r_min > 0, R_flat >= r_min, fit_edges > 0, sharp angle > 0, max offset > 0");
  const std::size_t nf = triangles_.size();
  const int nv = static_cast<int>(vertices_.size());
  face_normals_.assign(nf, Vec3{});
  vertex_faces_.assign(vertices_.size(), {});
  std::size_t good = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = triangles_[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= nv) throw std::invalid_argument("MeshContact: triangle " + std::to_string(f) + " indexes no vertex");
      vertex_faces_[t[k]].push_back(static_cast<int>(f));
    }
    const Vec3 n = cross(sub(vertices_[t[1]], vertices_[t[0]]), sub(vertices_[t[2]], vertices_[t[0]]));
    const double len = norm(n);
    const double scale2 = dot(sub(vertices_[t[1]], vertices_[t[0]]), sub(vertices_[t[1]], vertices_[t[0]])) +
                          dot(sub(vertices_[t[2]], vertices_[t[0]]), sub(vertices_[t[2]], vertices_[t[0]]));
    if (len > 1e-12 * scale2) {  // a sliver this thin has no normal worth the name
      face_normals_[f] = scale(n, 1 / len);
      ++good;
    }
  }
  if (good == 0) throw std::invalid_argument("MeshContact: every triangle has zero area");

  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edges;  // (lo, hi) -> (face, k)
  for (std::size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = triangles_[f][k], v = triangles_[f][(k + 1) % 3];
      edges[{std::min(u, v), std::max(u, v)}].push_back({static_cast<int>(f), k});
    }
  neighbours_.assign(nf, {-1, -1, -1});
  sharp_.assign(nf, {false, false, false});
  std::vector<int> sharp_count(vertices_.size(), 0);
  std::vector<std::vector<int>> sharp_ends(vertices_.size());
  for (const auto& [key, uses] : edges) {
    if (uses.size() != 2)
      throw std::invalid_argument("MeshContact: edge " + std::to_string(key.first) + "-" + std::to_string(key.second) + " has " +
                                  std::to_string(uses.size()) + " triangles, a closed mesh 2");
    const auto [f, k] = uses[0];
    const auto [g, l] = uses[1];
    neighbours_[f][k] = g;
    neighbours_[g][l] = f;
    const Vec3 &n_f = face_normals_[f], &n_g = face_normals_[g];
    if (dot(n_f, n_f) == 0 || dot(n_g, n_g) == 0) continue;  // beside a zero-area face: no angle to judge
    // Convex when g's far corner lies behind f's plane; a concave crease is two contacts on its
    // faces, not one on a ridge, so only convex ones are sharp.
    const int far = triangles_[g][(l + 2) % 3];
    const bool convex = dot(sub(vertices_[far], vertices_[triangles_[f][k]]), n_f) < 0;
    if (convex && angle_between(n_f, n_g) > rule_.sharp_angle_rad) {
      sharp_[f][k] = sharp_[g][l] = true;
      ++sharp_count[key.first];
      ++sharp_count[key.second];
      sharp_ends[key.first].push_back(key.second);
      sharp_ends[key.second].push_back(key.first);
    }
  }
  corner_.assign(vertices_.size(), false);
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    if (sharp_count[v] >= 3) corner_[v] = true;
    if (sharp_count[v] == 2) {  // a crease through v: a corner where it turns
      const Vec3 d1 = sub(vertices_[sharp_ends[v][0]], vertices_[v]), d2 = sub(vertices_[sharp_ends[v][1]], vertices_[v]);
      corner_[v] = std::numbers::pi - angle_between(d1, d2) > rule_.sharp_angle_rad;
    }
  }
  component_.assign(nf, -1);
  int label = 0;
  for (std::size_t start = 0; start < nf; ++start) {
    if (component_[start] >= 0) continue;
    std::vector<int> stack{static_cast<int>(start)};
    component_[start] = label;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int g = neighbours_[f][k];
        if (!sharp_[f][k] && component_[g] < 0) {
          component_[g] = label;
          stack.push_back(g);
        }
      }
    }
    ++label;
  }
}

MeshContact::Nearest MeshContact::nearest(const Vec3& p) const {
  Nearest best;
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    if (dot(face_normals_[f], face_normals_[f]) == 0) continue;  // its edges belong to other faces too
    const auto& t = triangles_[f];
    const Vec3 q = nearest_on_triangle(p, vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
    const Vec3 d = sub(p, q);
    const double d2 = dot(d, d);
    if (d2 < best2) {
      best2 = d2;
      best = {static_cast<int>(f), q, 0};
    }
  }
  best.distance = std::sqrt(best2);
  return best;
}

Vec3 MeshContact::patch_normal(int vertex, int component) const {
  Vec3 n{};
  for (const int f : vertex_faces_[vertex]) {
    if (component_[f] != component) continue;
    const auto& t = triangles_[f];
    const int k = t[0] == vertex ? 0 : t[1] == vertex ? 1 : 2;
    const double angle = angle_between(sub(vertices_[t[(k + 1) % 3]], vertices_[vertex]), sub(vertices_[t[(k + 2) % 3]], vertices_[vertex]));
    n = add(n, scale(face_normals_[f], angle));
  }
  const double len = norm(n);
  return len > 0 ? scale(n, 1 / len) : n;
}

std::array<double, 2> MeshContact::fitted_curvatures(int face, const Vec3& q) const {
  // Neighbourhood: the patch's vertices near q, gathered by walking from the contact face across
  // non-sharp edges, so that a fit never straddles a ridge: those within rho = fit_edges times the
  // contact face's shortest edge (long thin faces along a cylinder must not widen the fit across
  // it), and at least the kQuartic nearest (within 2 rho) where fewer lie within rho.
  constexpr std::size_t kQuartic = 30;  // twice the quartic's 15 unknowns
  const auto& t0 = triangles_[face];
  double shortest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) shortest = std::min(shortest, norm(sub(vertices_[t0[(k + 1) % 3]], vertices_[t0[k]])));
  const double rho = rule_.fit_edges * shortest;
  const int comp = component_[face];
  std::vector<std::pair<double, int>> near;  // (distance, vertex)
  std::vector<char> seen_face(triangles_.size(), 0), seen_vertex(vertices_.size(), 0);
  std::vector<int> stack{face};
  seen_face[face] = 1;
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (const int v : triangles_[f])
      if (!seen_vertex[v]) {
        seen_vertex[v] = 1;
        // Past 60 degrees from the contact face, a height field over its plane means little.
        if (dot(patch_normal(v, comp), face_normals_[face]) >= 0.5) near.push_back({norm(sub(vertices_[v], q)), v});
      }
    for (int k = 0; k < 3; ++k) {
      const int g = neighbours_[f][k];
      if (sharp_[f][k] || seen_face[g]) continue;
      const auto& tg = triangles_[g];
      if (norm(sub(q, nearest_on_triangle(q, vertices_[tg[0]], vertices_[tg[1]], vertices_[tg[2]]))) > 2 * rho) continue;
      seen_face[g] = 1;
      stack.push_back(g);
    }
  }
  std::sort(near.begin(), near.end());
  std::size_t count = 0;
  while (count < near.size() && (near[count].first <= rho || count < kQuartic)) ++count;
  near.resize(count);
  if (near.empty()) return {0, 0};  // no vertex faces the contact face's way: nothing to fit, flat
  const double span = std::max(near.back().first, rho);
  // Local frame at q: z along the contact face's outward normal; lengths in units of span.
  const Vec3 n = face_normals_[face];
  const Vec3 helper = std::abs(n[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 t1 = cross(helper, n);
  t1 = scale(t1, 1 / norm(t1));
  const Vec3 t2 = cross(n, t1);
  // The height field h(u, v) = c0 u^2 + c1 u v + c2 v^2 + c3 u + c4 v + c5, plus the cubic and
  // quartic terms where kQuartic points fix them: those soak up a sphere's r^4 / 8 R^3, which a
  // quadric alone folds into its curvature (-0.44 (rho / R)^2 relative: -3 % on a 1280-triangle
  // icosphere at rho = 2 edges). The quartic fits heights only: a vertex normal averaged over its
  // faces is off by O(h^2), a slope error that is O(h) of the curvature (4 % there). Fewer points
  // (a coarse mesh, a small flat face) fit the quadric to heights and normals, which one triangle's
  // corners determine.
  const bool quartic = near.size() >= kQuartic;
  const int unknowns = quartic ? 15 : 6;
  using Row = std::array<double, 15>;
  std::vector<Row> rows;
  std::vector<double> rhs;
  for (const auto& [distance, v] : near) {
    const Vec3 d = scale(sub(vertices_[v], q), 1 / span);
    const double u = dot(d, t1), w = dot(d, t2), h = dot(d, n);
    rows.push_back({u * u, u * w, w * w, u, w, 1, u * u * u, u * u * w, u * w * w, w * w * w, u * u * u * u, u * u * u * w,
                    u * u * w * w, u * w * w * w, w * w * w * w});
    rhs.push_back(h);
    if (quartic) continue;
    const Vec3 nv = patch_normal(v, comp);
    const double nz = dot(nv, n);  // >= 0.5, as gathered
    rows.push_back({2 * u, w, 0, 1, 0, 0});
    rhs.push_back(-dot(nv, t1) / nz);
    rows.push_back({0, u, 2 * w, 0, 1, 0});
    rhs.push_back(-dot(nv, t2) / nz);
  }
  Eigen::MatrixXd a(static_cast<Eigen::Index>(rows.size()), unknowns);
  Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (int c = 0; c < unknowns; ++c) a(static_cast<Eigen::Index>(r), c) = rows[r][static_cast<std::size_t>(c)];
    b(static_cast<Eigen::Index>(r)) = rhs[r];
  }
  // Minimum norm: a direction the data leave undetermined gets zero curvature (flat, then clamped).
  const Eigen::VectorXd c = a.completeOrthogonalDecomposition().solve(b);
  // Curvature of the graph at (0, 0): shape operator S = -I^-1 II with I = 1 + grad grad^T and
  // II = Hessian / sqrt(1 + |grad|^2); positive where the surface bends away from its normal.
  const double p = c(3), s = c(4), g = 1 + p * p + s * s;
  const double hxx = 2 * c(0) / span, hxy = c(1) / span, hyy = 2 * c(2) / span, root_g = std::sqrt(g);
  const double iixx = hxx / root_g, iixy = hxy / root_g, iiyy = hyy / root_g;
  const double sxx = -((1 + s * s) * iixx - p * s * iixy) / g, syy = -(-p * s * iixy + (1 + p * p) * iiyy) / g;
  const double mean = (sxx + syy) / 2, gauss = (iixx * iiyy - iixy * iixy) / g;
  const double spread = std::sqrt(std::max(mean * mean - gauss, 0.0));
  return {mean + spread, mean - spread};
}

MeshContactPoint MeshContact::at(const Vec3& point_m) const {
  for (const double x : point_m)
    if (!std::isfinite(x)) throw std::invalid_argument("MeshContact: contact point is not finite");
  const Nearest near = nearest(point_m);
  if (near.distance > rule_.max_offset_m)
    throw std::invalid_argument("contact point " + std::to_string(near.distance) + " m from the mesh's surface (at most " +
                                std::to_string(rule_.max_offset_m) + " m, half the mesh's reach from its centre)");
  MeshContactPoint out;
  out.surface_point_m = near.point;
  out.offset_m = near.distance;
  const double r_min = rule_.rounding_radius_m, r_flat = rule_.flat_radius_m;
  // Sharp features within r_min of q: on the faces of q's smooth patch that come that close.
  const Vec3& q = near.point;
  bool on_corner = false, on_edge = false;
  std::vector<int> stack{near.face};
  std::vector<int> visited{near.face};
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    const auto& t = triangles_[f];
    for (int k = 0; k < 3; ++k) {
      if (corner_[t[k]] && norm(sub(vertices_[t[k]], q)) <= r_min) on_corner = true;
      if (sharp_[f][k] && segment_distance(q, vertices_[t[k]], vertices_[t[(k + 1) % 3]]) <= r_min) on_edge = true;
      const int g = neighbours_[f][k];
      if (sharp_[f][k] || std::find(visited.begin(), visited.end(), g) != visited.end()) continue;
      const auto& tg = triangles_[g];
      if (norm(sub(q, nearest_on_triangle(q, vertices_[tg[0]], vertices_[tg[1]], vertices_[tg[2]]))) > r_min) continue;
      visited.push_back(g);
      stack.push_back(g);
    }
  }
  double k1 = 0, k2 = 0;
  if (on_corner) {
    out.feature = ContactFeature::corner;
    k1 = k2 = 1 / r_min;
  } else if (on_edge) {
    out.feature = ContactFeature::edge;
    k1 = 1 / r_min;
    k2 = 1 / r_flat;
  } else {
    const auto k = fitted_curvatures(near.face, q);
    k1 = std::clamp(k[0], 1 / r_flat, 1 / r_min);
    k2 = std::clamp(k[1], 1 / r_flat, 1 / r_min);
  }
  out.curvature_1_per_m = std::max(k1, k2);
  out.curvature_2_per_m = std::min(k1, k2);
  out.radius_m = 1 / std::sqrt(k1 * k2);
  return out;
}

}  // namespace clatter::kernels
