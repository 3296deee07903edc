#include <Eigen/Geometry>

#include <algorithm>
#include <numbers>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/fem/object_parts.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

std::int64_t edge_key(int a, int b) {
  return static_cast<std::int64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b));
}

using V3 = Eigen::Vector3d;
V3 vec(const P3& p) { return {p[0], p[1], p[2]}; }

// Barycentric coordinates of x in the plane of (a, b, c), outside it too (not clamped).
P3 planar_barycentric(const V3& x, const V3& a, const V3& b, const V3& c) {
  const V3 v0 = b - a, v1 = c - a, v2 = x - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double det = d00 * d11 - d01 * d01, w1 = (d11 * d20 - d01 * d21) / det, w2 = (d00 * d21 - d01 * d20) / det;
  return {1 - w1 - w2, w1, w2};
}

class Bisection {
 public:
  Bisection(RefinedSurface& s, const SmoothSurface& surface, const std::vector<P3>& vertices,
            const std::vector<std::array<int, 3>>& triangles, std::int64_t max_facets)
      : s_(s), surface_(surface), vertices_(vertices), triangles_(triangles), max_facets_(max_facets) {
    for (std::size_t f = 0; f < s_.facets.size(); ++f)
      for (int k = 0; k < 3; ++k) attach(s_.facets[f][k], s_.facets[f][(k + 1) % 3], static_cast<int>(f));
  }

  // Every edge longer than its ends' mean size, longest first, until none is left.
  void run() {
    for (;;) {
      std::vector<std::pair<double, std::int64_t>> long_edges;
      for (const auto& [key, faces] : edges_) {
        const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffff);
        if (length(a, b) > 0.5 * (s_.size_m[a] + s_.size_m[b])) long_edges.push_back({length(a, b), key});
      }
      if (long_edges.empty()) return;
      std::sort(long_edges.begin(), long_edges.end(), std::greater<>());
      for (const auto& [l, key] : long_edges)
        if (edges_.count(key)) bisect(static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffff));
    }
  }

 private:
  double length(int a, int b) const {
    const P3 &p = s_.points_m[a], &q = s_.points_m[b];
    return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
  }

  void attach(int a, int b, int f) {
    auto [it, fresh] = edges_.try_emplace(edge_key(a, b), std::array<int, 2>{f, -1});
    if (!fresh) it->second[1] = f;
  }
  void replace(int a, int b, int old_f, int new_f) {
    auto& faces = edges_.at(edge_key(a, b));
    (faces[0] == old_f ? faces[0] : faces[1]) = new_f;
  }

  // The facet's longest edge, ties broken by the key: a total order, so the recursion ends.
  std::int64_t longest(int f) const {
    std::pair<double, std::int64_t> best{-1, 0};
    for (int k = 0; k < 3; ++k) {
      const int a = s_.facets[f][k], b = s_.facets[f][(k + 1) % 3];
      best = std::max(best, {length(a, b), edge_key(a, b)});
    }
    return best.second;
  }

  void bisect(int a, int b) {
    const std::int64_t key = edge_key(a, b);
    for (int side = 0; side < 2; ++side)
      for (;;) {
        const int f = edges_.at(key)[side];
        const std::int64_t l = longest(f);
        if (l == key) break;
        bisect(static_cast<int>(l >> 32), static_cast<int>(l & 0xffffffff));
      }
    const std::array<int, 2> faces = edges_.at(key);
    edges_.erase(key);
    const int m = static_cast<int>(s_.points_m.size());
    s_.size_m.push_back(0.5 * (s_.size_m[a] + s_.size_m[b]));
    s_.points_m.push_back({});
    for (int side = 0; side < 2; ++side) split(faces[side], a, b, m, side == 0);
    if (static_cast<std::int64_t>(s_.facets.size()) > max_facets_)
      throw MeshError("object mesh", "the surface needs more than " + std::to_string(max_facets_) +
                                         " triangles at the sizes asked (edge length or thickness too small?)");
  }

  // Facet f = (.., a, b, ..) becomes (p, m, c) and a new facet (m, q, c), (p, q) = its (a, b) in order.
  void split(int f, int a, int b, int m, bool place) {
    auto& v = s_.facets[f];
    const int k = (v[0] == a || v[0] == b) && (v[1] == a || v[1] == b) ? 0 : (v[1] == a || v[1] == b) && (v[2] == a || v[2] == b) ? 1 : 2;
    const int p = v[k], q = v[(k + 1) % 3], c = v[(k + 2) % 3];
    auto bary = s_.corner_barycentric[f];
    P3 mid{};
    for (int i = 0; i < 3; ++i) mid[i] = 0.5 * (bary[k][i] + bary[(k + 1) % 3][i]);
    if (place) s_.points_m[m] = surface_.point(s_.source[f], mid);
    const int g = static_cast<int>(s_.facets.size());
    std::array<P3, 3> bary_g{};
    bary_g[k] = mid, bary_g[(k + 1) % 3] = bary[(k + 1) % 3], bary_g[(k + 2) % 3] = bary[(k + 2) % 3];
    std::array<int, 3> w = v;
    w[k] = m;  // (m, q, c) in f's corner order
    v[(k + 1) % 3] = m;  // (p, m, c)
    s_.corner_barycentric[f][(k + 1) % 3] = mid;
    s_.facets.push_back(w);
    s_.source.push_back(s_.source[f]);
    s_.corner_barycentric.push_back(bary_g);
    replace(q, c, f, g);
    attach(p, m, f), attach(m, q, g), attach(m, c, f), attach(m, c, g);
  }

  V3 point(int v) const { return vec(s_.points_m[v]); }
  V3 facet_normal(int p, int q, int r) const { return (point(q) - point(p)).cross(point(r) - point(p)); }

  // The input edge of `source` that both barycentric points lie on, or -1.
  static int input_edge(const P3& a, const P3& b) {
    for (int e = 0; e < 3; ++e)
      if (a[(e + 2) % 3] == 0 && b[(e + 2) % 3] == 0) return e;
    return -1;
  }

  // Flip edge key's diagonal where the quadrilateral of its two facets is not Delaunay (angles
  // opposite it sum over pi) and the flip keeps the facets on the smooth surface: both facets in
  // one input triangle (the barycentric map is linear inside it), or in two flat, coplanar ones
  // across an edge that is not sharp (the plane is the surface there, so the new facets may leave
  // their source triangle).
  bool flip(std::int64_t key) {
    const std::array<int, 2> fg = edges_.at(key);
    const int f = fg[0], g = fg[1], a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffff);
    const auto& vf = s_.facets[f];
    const int k = (vf[0] == a || vf[0] == b) && (vf[1] == a || vf[1] == b) ? 0 : (vf[1] == a || vf[1] == b) && (vf[2] == a || vf[2] == b) ? 1 : 2;
    const int p = vf[k], q = vf[(k + 1) % 3], c = vf[(k + 2) % 3];
    const auto& vg = s_.facets[g];
    const int d = vg[0] != p && vg[0] != q ? vg[0] : vg[1] != p && vg[1] != q ? vg[1] : vg[2];
    if (edges_.count(edge_key(c, d))) return false;
    const int sf = s_.source[f], sg = s_.source[g];
    const auto &bf = s_.corner_barycentric[f], &bg = s_.corner_barycentric[g];
    P3 at_d{};
    if (sf == sg) {
      at_d = bg[vg[0] == d ? 0 : vg[1] == d ? 1 : 2];
    } else {
      const int e = input_edge(bf[k], bf[(k + 1) % 3]);
      const V3 nf = facet_normal(p, q, c).normalized(), ng = facet_normal(q, p, d).normalized();
      if (e < 0 || surface_.sharp(sf, e) || !surface_.flat(sf) || !surface_.flat(sg) || nf.dot(ng) < 1 - 1e-14) return false;
      const auto& t = triangles_[sf];
      at_d = planar_barycentric(point(d), vec(vertices_[t[0]]), vec(vertices_[t[1]]), vec(vertices_[t[2]]));
    }
    auto angle = [&](int at, int u, int w) {
      const V3 x = point(u) - point(at), y = point(w) - point(at);
      return std::atan2(x.cross(y).norm(), x.dot(y));
    };
    if (!(angle(c, p, q) + angle(d, q, p) > std::numbers::pi * (1 + 1e-9))) return false;
    // The new facets face as the old did (the quadrilateral is convex).
    const V3 n = facet_normal(p, q, c) + facet_normal(q, p, d);
    if (!(facet_normal(p, d, c).dot(n) > 0) || !(facet_normal(d, q, c).dot(n) > 0)) return false;
    const P3 at_p = bf[k], at_q = bf[(k + 1) % 3], at_c = bf[(k + 2) % 3];
    s_.facets[f] = {p, d, c}, s_.corner_barycentric[f] = {at_p, at_d, at_c};
    s_.facets[g] = {d, q, c}, s_.corner_barycentric[g] = {at_d, at_q, at_c}, s_.source[g] = sf;
    edges_.erase(key);
    replace(q, c, f, g), replace(p, d, g, f);
    attach(c, d, f), attach(c, d, g);
    return true;
  }

 public:
  // Flips as above until none is left (a few passes, edges in a fixed order).
  void flip_all() {
    for (int pass = 0; pass < 50; ++pass) {
      std::vector<std::int64_t> keys;
      keys.reserve(edges_.size());
      for (const auto& entry : edges_) keys.push_back(entry.first);
      std::sort(keys.begin(), keys.end());
      int flips = 0;
      for (std::int64_t key : keys) flips += edges_.count(key) && flip(key);
      if (flips == 0) return;
    }
  }

  // Bisecting a long, thin input triangle leaves a row of points along its diagonal close to its
  // long edges, which no flip removes: in flat regions each point moves to its neighbours' mean
  // (where no facet around it turns over), then the flips run again.
  void improve() {
    flip_all();
    for (int round = 0; round < 8; ++round) {
      const bool merged = merge_close_points() > 0;
      flip_all();
      smooth_flat_points();
      flip_all();
      if (!merged && round >= 3) break;
    }
  }

 private:
  // v's facets all flat, in one plane, and v on no sharp input edge: v may move within the plane.
  bool free_in_plane(int v, const std::vector<int>& around, V3& plane_normal) const {
    bool first = true;
    for (int f : around) {
      const int src = s_.source[f];
      if (!surface_.flat(src)) return false;
      const auto& vf = s_.facets[f];
      const V3 n = facet_normal(vf[0], vf[1], vf[2]).normalized();
      if (first) plane_normal = n, first = false;
      else if (n.dot(plane_normal) < 1 - 1e-12) return false;
      const P3& at = s_.corner_barycentric[f][vf[0] == v ? 0 : vf[1] == v ? 1 : 2];
      for (int e = 0; e < 3; ++e)
        if (std::abs(at[(e + 2) % 3]) < 1e-12 && surface_.sharp(src, e)) return false;
    }
    return !first;
  }

  // Twice the smallest area of the facets, each counted facing the plane's normal.
  double smallest_area(const std::vector<int>& facets, const V3& plane) const {
    double least = std::numeric_limits<double>::infinity();
    for (int f : facets) {
      const auto& w = s_.facets[f];
      if (!dead_.empty() && dead_[f]) continue;
      least = std::min(least, facet_normal(w[0], w[1], w[2]).dot(plane));
    }
    return least;
  }

  // A free point closer than a third of its size to a neighbour is merged into the nearest
  // neighbour it can be (the facets left keep their side, none flat); the fans of input triangles
  // about one vertex (a disk's cap) leave such clusters near their centre. True where it merged.
  int merge_close_points() {
    std::vector<std::vector<int>> around(s_.points_m.size());
    for (std::size_t f = 0; f < s_.facets.size(); ++f)
      for (int v : s_.facets[f]) around[v].push_back(static_cast<int>(f));
    std::vector<bool> touched(s_.points_m.size(), false);
    dead_.assign(s_.facets.size(), false);
    int merged = 0;
    for (std::size_t vi = 0; vi < s_.points_m.size(); ++vi) {
      const int v = static_cast<int>(vi);
      V3 plane = V3::Zero();
      if (touched[v] || around[v].empty() || !free_in_plane(v, around[v], plane)) continue;
      std::vector<std::pair<double, int>> near;
      for (int f : around[v])
        for (int w : s_.facets[f]) {
          const double d = (point(w) - point(v)).norm();
          if (w != v && d < s_.size_m[v] / 3 && !touched[w]) near.push_back({d, w});
        }
      std::sort(near.begin(), near.end());
      for (const auto& [d, u] : near) {
        if (!merge(v, u, around[v], plane)) continue;
        for (int f : around[v])
          for (int w : s_.facets[f]) touched[w] = true;
        ++merged;
        break;
      }
    }
    if (merged > 0) compact();
    dead_.clear();
    return merged;
  }

  bool merge(int v, int u, const std::vector<int>& around, const V3& plane) {
    const double floor = 1e-3 * s_.size_m[v] * s_.size_m[v];
    for (int f : around) {
      std::array<int, 3> w = s_.facets[f];
      if (w[0] == u || w[1] == u || w[2] == u) continue;
      for (int& x : w) x = x == v ? u : x;
      if (!(facet_normal(w[0], w[1], w[2]).dot(plane) > floor)) return false;
    }
    for (int f : around) {
      auto& w = s_.facets[f];
      if (w[0] == u || w[1] == u || w[2] == u) {
        dead_[f] = true;
        continue;
      }
      const int k = w[0] == v ? 0 : w[1] == v ? 1 : 2;
      w[k] = u;
      const auto& t = triangles_[s_.source[f]];
      s_.corner_barycentric[f][k] = planar_barycentric(point(u), vec(vertices_[t[0]]), vec(vertices_[t[1]]), vec(vertices_[t[2]]));
    }
    return true;
  }

  // Drops the dead facets and the points on no facet (TetGen would take a point on a facet but
  // in none for an interior point), and remakes the edge map.
  void compact() {
    RefinedSurface kept;
    std::vector<int> index(s_.points_m.size(), -1);
    for (std::size_t f = 0; f < s_.facets.size(); ++f) {
      if (dead_[f]) continue;
      std::array<int, 3> w = s_.facets[f];
      for (int& x : w) {
        if (index[x] < 0) {
          index[x] = static_cast<int>(kept.points_m.size());
          kept.points_m.push_back(s_.points_m[x]);
          kept.size_m.push_back(s_.size_m[x]);
        }
        x = index[x];
      }
      kept.facets.push_back(w);
      kept.source.push_back(s_.source[f]);
      kept.corner_barycentric.push_back(s_.corner_barycentric[f]);
    }
    s_ = std::move(kept);
    edges_.clear();
    for (std::size_t f = 0; f < s_.facets.size(); ++f)
      for (int k = 0; k < 3; ++k) attach(s_.facets[f][k], s_.facets[f][(k + 1) % 3], static_cast<int>(f));
  }

  void smooth_flat_points() {
    std::vector<std::vector<int>> around(s_.points_m.size());
    for (std::size_t f = 0; f < s_.facets.size(); ++f)
      for (int v : s_.facets[f]) around[v].push_back(static_cast<int>(f));
    for (std::size_t vi = 0; vi < s_.points_m.size(); ++vi) {
      const int v = static_cast<int>(vi);
      V3 plane = V3::Zero();
      if (around[v].empty() || !free_in_plane(v, around[v], plane)) continue;
      V3 sum = V3::Zero();
      for (int f : around[v])  // each neighbour twice (two facets share each edge out of v)
        for (int w : s_.facets[f])
          if (w != v) sum += point(w);
      const P3 old = s_.points_m[v];
      const double before = smallest_area(around[v], plane);
      const V3 moved = sum / (2.0 * static_cast<double>(around[v].size()));
      s_.points_m[v] = {moved(0), moved(1), moved(2)};
      if (!(smallest_area(around[v], plane) >= std::max(before, 0.0))) {  // the worst facet around v may only grow
        s_.points_m[v] = old;
        continue;
      }
      for (int f : around[v]) {
        const auto& w = s_.facets[f];
        const auto& t = triangles_[s_.source[f]];
        s_.corner_barycentric[f][w[0] == v ? 0 : w[1] == v ? 1 : 2] =
            planar_barycentric(moved, vec(vertices_[t[0]]), vec(vertices_[t[1]]), vec(vertices_[t[2]]));
      }
    }
  }

 private:
  RefinedSurface& s_;
  const SmoothSurface& surface_;
  const std::vector<P3>& vertices_;
  const std::vector<std::array<int, 3>>& triangles_;
  std::int64_t max_facets_;
  std::unordered_map<std::int64_t, std::array<int, 2>> edges_;
  std::vector<bool> dead_;  // facets merge_close_points removed
};

}  // namespace

RefinedSurface refine_surface(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                              const SmoothSurface& surface, const std::vector<double>& vertex_size_m, std::int64_t max_facets) {
  RefinedSurface s;
  s.points_m = vertices;
  s.size_m = vertex_size_m;
  s.facets = triangles;
  s.source.resize(triangles.size());
  s.corner_barycentric.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    s.source[t] = static_cast<int>(t);
    s.corner_barycentric[t] = {P3{1, 0, 0}, P3{0, 1, 0}, P3{0, 0, 1}};
  }
  Bisection refinement(s, surface, vertices, triangles, max_facets);
  refinement.run();
  refinement.improve();
  return s;
}

}  // namespace clatter::kernels::fem
