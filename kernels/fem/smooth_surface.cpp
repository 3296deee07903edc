#include "kernels/fem/smooth_surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace clatter::kernels::fem {
namespace {

using V3 = Eigen::Vector3d;
using P3 = std::array<double, 3>;

V3 vec(const P3& p) { return {p[0], p[1], p[2]}; }
P3 arr(const V3& v) { return {v(0), v(1), v(2)}; }

// The corner slots (3 t + k) of one vertex joined across its smooth edges: one root per sector.
class Sectors {
 public:
  explicit Sectors(std::size_t slots) : parent_(slots) { std::iota(parent_.begin(), parent_.end(), 0); }
  int root(int s) {
    while (parent_[s] != s) s = parent_[s] = parent_[parent_[s]];
    return s;
  }
  void join(int a, int b) { parent_[root(a)] = root(b); }

 private:
  std::vector<int> parent_;
};

int corner_of(const std::array<int, 3>& f, int v) { return f[0] == v ? 0 : f[1] == v ? 1 : 2; }

std::int64_t edge_key(int a, int b) {
  return static_cast<std::int64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b));
}

// Barycentric coordinates of x projected into the plane of (a, b, c), outside it too.
P3 planar_barycentric(const V3& x, const V3& a, const V3& b, const V3& c) {
  const V3 v0 = b - a, v1 = c - a, v2 = x - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double det = d00 * d11 - d01 * d01, w1 = (d11 * d20 - d01 * d21) / det, w2 = (d00 * d21 - d01 * d20) / det;
  return {1 - w1 - w2, w1, w2};
}

}  // namespace

SmoothSurface::SmoothSurface(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                             double smooth_dihedral_deg) {
  const std::size_t nt = triangles.size();
  std::vector<V3> normal(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& f = triangles[t];
    normal[t] =
        (vec(vertices[f[1]]) - vec(vertices[f[0]])).cross(vec(vertices[f[2]]) - vec(vertices[f[0]])).normalized();
  }
  // Each undirected edge with its two triangles (the surface is closed and manifold).
  std::map<std::pair<int, int>, std::array<int, 2>> edge_faces;
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      auto [it, fresh] =
          edge_faces.try_emplace({std::min(a, b), std::max(a, b)}, std::array<int, 2>{static_cast<int>(t), -1});
      if (!fresh) it->second[1] = static_cast<int>(t);
    }
  const double cos_limit = std::cos(smooth_dihedral_deg * std::numbers::pi / 180);
  sharp_.assign(nt, {false, false, false});
  Sectors sectors(3 * nt);
  for (const auto& [e, f] : edge_faces) {
    ++edges_;
    if (f[1] < 0) continue;
    // Normals turning by smooth_dihedral_deg or more: sharp (0 degrees makes every edge sharp).
    const bool sharp = !(normal[f[0]].dot(normal[f[1]]) > cos_limit) || smooth_dihedral_deg <= 0;
    for (int side = 0; side < 2; ++side) {
      const auto& tri = triangles[f[side]];
      const int k = corner_of(tri, e.first), j = corner_of(tri, e.second);
      sharp_[f[side]][(j == (k + 1) % 3) ? k : j] = sharp;
    }
    sharp_edges_ += sharp;
    if (sharp) continue;
    for (int v : {e.first, e.second})
      sectors.join(3 * f[0] + corner_of(triangles[f[0]], v), 3 * f[1] + corner_of(triangles[f[1]], v));
  }
  // Angle-weighted normal per sector (independent of how the sector is cut into triangles).
  std::vector<V3> sum(3 * nt, V3::Zero());
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto& f = triangles[t];
      const V3 p = vec(vertices[f[k]]), u = vec(vertices[f[(k + 1) % 3]]) - p, w = vec(vertices[f[(k + 2) % 3]]) - p;
      sum[sectors.root(static_cast<int>(3 * t) + k)] += std::atan2(u.cross(w).norm(), u.dot(w)) * normal[t];
    }
  control_m_.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& f = triangles[t];
    V3 p[3], n[3];
    for (int k = 0; k < 3; ++k)
      p[k] = vec(vertices[f[k]]), n[k] = sum[sectors.root(static_cast<int>(3 * t) + k)].normalized();
    // Edge control point near corner i towards j: the third point projected into i's tangent plane.
    auto edge_point = [&](int i, int j, int k_edge) {
      const double w = sharp_[t][k_edge] ? 0.0 : (p[j] - p[i]).dot(n[i]);
      return V3((2 * p[i] + p[j] - w * n[i]) / 3);
    };
    const V3 b210 = edge_point(0, 1, 0), b120 = edge_point(1, 0, 0), b021 = edge_point(1, 2, 1),
             b012 = edge_point(2, 1, 1), b102 = edge_point(2, 0, 2), b201 = edge_point(0, 2, 2);
    const V3 e = (b210 + b120 + b021 + b012 + b102 + b201) / 6, v = (p[0] + p[1] + p[2]) / 3;
    control_m_[t] = {arr(p[0]), arr(p[1]), arr(p[2]), arr(b210), arr(b120),
                     arr(b021), arr(b012), arr(b102), arr(b201), arr(e + (e - v) / 2)};
  }
}

P3 SmoothSurface::point(int t, const P3& b) const {
  const auto& c = control_m_[static_cast<std::size_t>(t)];
  const double u = b[0], v = b[1], w = b[2];
  const double weight[10] = {u * u * u,     v * v * v,     w * w * w,     3 * u * u * v, 3 * u * v * v,
                             3 * v * v * w, 3 * v * w * w, 3 * u * w * w, 3 * u * u * w, 6 * u * v * w};
  P3 x{0, 0, 0};
  for (int i = 0; i < 10; ++i)
    for (int k = 0; k < 3; ++k) x[k] += weight[i] * c[i][k];
  return x;
}

SurfaceProjector::SurfaceProjector(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                                   const SmoothSurface& surface)
    : vertices_(vertices), triangles_(triangles), surface_(surface), across_(triangles.size(), {-1, -1, -1}) {
  std::unordered_map<std::int64_t, std::pair<int, int>> first;  // edge -> (triangle, edge index)
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto [it, fresh] =
          first.try_emplace(edge_key(triangles[t][k], triangles[t][(k + 1) % 3]), static_cast<int>(t), k);
      if (fresh) continue;
      across_[t][k] = it->second.first;
      across_[it->second.first][it->second.second] = static_cast<int>(t);
    }
}

// The foot of x on triangle t's patch: from the flat triangle's barycentric coordinates, Gauss-
// Newton on |x - P(b)|^2 (derivatives by central differences: they steer the steps only, the
// point returned is P(b) itself, on the patch). Coordinates may leave [0, 1]: x is then over a
// neighbour. Projecting onto the flat triangles alone would leave gaps over convex corners, where
// a point above the flat faces (as the patches are) is over none of them.
P3 SurfaceProjector::foot(int t, const P3& x) const {
  const auto& f = triangles_[t];
  P3 w = planar_barycentric(vec(x), vec(vertices_[f[0]]), vec(vertices_[f[1]]), vec(vertices_[f[2]]));
  constexpr double kStep = 1e-5;
  for (int iteration = 0; iteration < 4; ++iteration) {
    auto at = [&](double du, double dv) { return vec(surface_.point(t, {w[0] - du - dv, w[1] + du, w[2] + dv})); };
    const V3 p = at(0, 0), pu = (at(kStep, 0) - at(-kStep, 0)) / (2 * kStep),
             pv = (at(0, kStep) - at(0, -kStep)) / (2 * kStep);
    const V3 r = vec(x) - p;
    const double a = pu.dot(pu), b = pu.dot(pv), c = pv.dot(pv), det = a * c - b * b;
    if (!(det > 0)) break;
    const double du = (c * pu.dot(r) - b * pv.dot(r)) / det, dv = (a * pv.dot(r) - b * pu.dot(r)) / det;
    w = {w[0] - du - dv, w[1] + du, w[2] + dv};
  }
  return w;
}

P3 SurfaceProjector::project(const P3& x, int& triangle) const {
  // The walk leaves across the edge opposite the most negative coordinate; on a closed surface
  // it ends within a few steps of a nearby start (a bound keeps a cycle, as across a sharp edge
  // whose faces' feet each lie over the other, from looping: the least outside is taken).
  int best = triangle;
  P3 best_w{};
  double best_outside = std::numeric_limits<double>::infinity();
  for (int step = 0, t = triangle; step < 64 && t >= 0; ++step) {
    const P3 w = foot(t, x);
    const int worst = static_cast<int>(std::min_element(w.begin(), w.end()) - w.begin());
    if (-w[worst] < best_outside) best = t, best_w = w, best_outside = -w[worst];
    if (w[worst] >= -1e-12) break;
    t = across_[t][(worst + 1) % 3];  // corner `worst` is opposite edge worst + 1
  }
  double sum = 0;
  for (double& c : best_w) sum += (c = std::max(c, 0.0));
  for (double& c : best_w) c /= sum;
  triangle = best;
  return surface_.point(best, best_w);
}

namespace {

// A bounding-volume tree over triangles, split at the median centroid along the widest axis.
struct Bvh {
  struct Node {
    V3 lo, hi;
    int left = -1, right = -1, first = 0, count = 0;
  };
  std::vector<Node> nodes;
  std::vector<int> order;
  const std::vector<P3>* vertices;
  const std::vector<std::array<int, 3>>* triangles;

  V3 corner(int t, int k) const { return vec((*vertices)[(*triangles)[t][k]]); }

  int build(int first, int count, const std::vector<V3>& centroid) {
    Node node;
    node.lo = V3::Constant(std::numeric_limits<double>::infinity()), node.hi = -node.lo;
    for (int i = first; i < first + count; ++i)
      for (int k = 0; k < 3; ++k)
        node.lo = node.lo.cwiseMin(corner(order[i], k)), node.hi = node.hi.cwiseMax(corner(order[i], k));
    const int index = static_cast<int>(nodes.size());
    nodes.push_back(node);
    if (count <= 4) {
      nodes[index].first = first, nodes[index].count = count;
      return index;
    }
    int axis = 0;
    (node.hi - node.lo).maxCoeff(&axis);
    const auto mid = order.begin() + first + count / 2;
    std::nth_element(order.begin() + first, mid, order.begin() + first + count, [&](int a, int b) {
      return centroid[a](axis) < centroid[b](axis) || (centroid[a](axis) == centroid[b](axis) && a < b);
    });
    const int left = build(first, count / 2, centroid), right = build(first + count / 2, count - count / 2, centroid);
    nodes[index].left = left, nodes[index].right = right;
    return index;
  }

  static bool box_hit(const Node& n, const V3& o, const V3& inv_d, double t_max) {
    double t0 = 0, t1 = t_max;
    for (int k = 0; k < 3; ++k) {
      double a = (n.lo(k) - o(k)) * inv_d(k), b = (n.hi(k) - o(k)) * inv_d(k);
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a), t1 = std::min(t1, b);
    }
    return t0 <= t1;
  }

  // Moller-Trumbore: the ray's parameter at triangle t, or infinity.
  double hit(int t, const V3& o, const V3& d) const {
    const V3 a = corner(t, 0), e1 = corner(t, 1) - a, e2 = corner(t, 2) - a, p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) return std::numeric_limits<double>::infinity();
    const V3 s = o - a;
    const double u = s.dot(p) / det;
    if (u < 0 || u > 1) return std::numeric_limits<double>::infinity();
    const V3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0 || u + v > 1) return std::numeric_limits<double>::infinity();
    return e2.dot(q) / det;
  }

  double nearest(const V3& o, const V3& d, int skip) const {
    const V3 inv_d = d.cwiseInverse();
    double best = std::numeric_limits<double>::infinity();
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const Node& n = nodes[stack.back()];
      stack.pop_back();
      if (!box_hit(n, o, inv_d, best)) continue;
      if (n.left >= 0) {
        stack.push_back(n.left), stack.push_back(n.right);
        continue;
      }
      for (int i = n.first; i < n.first + n.count; ++i)
        if (order[i] != skip) {
          const double t = hit(order[i], o, d);
          if (t > 0 && t < best) best = t;
        }
    }
    return best;
  }
};

}  // namespace

namespace {

// Per triangle in `which`, the distance from its centroid along sign times its normal to the
// nearest other triangle, at most the bounding box's diagonal; and the centroids and normals.
std::vector<double> ray_distances_m(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                                    const std::vector<int>& which, double sign, std::vector<V3>& centroid,
                                    std::vector<V3>& direction) {
  const int nt = static_cast<int>(triangles.size());
  Bvh tree;
  tree.vertices = &vertices, tree.triangles = &triangles;
  tree.order.resize(nt);
  std::iota(tree.order.begin(), tree.order.end(), 0);
  centroid.resize(nt), direction.resize(nt);
  for (int t = 0; t < nt; ++t) {
    centroid[t] = (tree.corner(t, 0) + tree.corner(t, 1) + tree.corner(t, 2)) / 3;
    direction[t] =
        sign * (tree.corner(t, 1) - tree.corner(t, 0)).cross(tree.corner(t, 2) - tree.corner(t, 0)).normalized();
  }
  tree.build(0, nt, centroid);
  const double reach = (tree.nodes[0].hi - tree.nodes[0].lo).norm();
  std::vector<double> out;
  for (int t : which) out.push_back(std::min(tree.nearest(centroid[t], direction[t], t), reach));
  return out;
}

}  // namespace

std::vector<P3> points_in_cavities_m(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                                     const std::vector<int>& facing) {
  if (facing.empty()) return {};
  std::vector<V3> centroid, outward;
  const std::vector<double> d = ray_distances_m(vertices, triangles, facing, 1.0, centroid, outward);
  std::vector<P3> out;
  for (std::size_t i = 0; i < facing.size(); ++i)
    out.push_back(arr(centroid[facing[i]] + 0.5 * d[i] * outward[facing[i]]));
  return out;
}

std::vector<double> thickness_under_triangles_m(const std::vector<P3>& vertices,
                                                const std::vector<std::array<int, 3>>& triangles) {
  std::vector<int> all(triangles.size());
  std::iota(all.begin(), all.end(), 0);
  std::vector<V3> centroid, inward;
  return ray_distances_m(vertices, triangles, all, -1.0, centroid, inward);
}

}  // namespace clatter::kernels::fem
