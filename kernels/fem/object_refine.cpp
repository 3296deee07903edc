#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <utility>

#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/fem/object_parts.hpp"

namespace clatter::kernels::fem {

std::int64_t undirected_edge_key(int a, int b) {
  return static_cast<std::int64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b));
}

namespace {

using P3 = std::array<double, 3>;
using V3 = Eigen::Vector3d;
V3 vec(const P3& p) { return {p[0], p[1], p[2]}; }

class Refinement {
 public:
  Refinement(RefinedSurface& s, const SurfaceProjector& projector, std::int64_t max_facets)
      : s_(s), projector_(projector), max_facets_(max_facets) {
    remake_edges();
  }

  // Every edge longer than its ends' mean size, longest first, until none is left.
  void bisect_all() {
    for (;;) {
      std::vector<std::pair<double, std::int64_t>> long_edges;
      for (const auto& entry : edges_) {
        const auto [a, b] = ends(entry.first);
        if (length(a, b) > 0.5 * (s_.size_m[a] + s_.size_m[b])) long_edges.push_back({length(a, b), entry.first});
      }
      if (long_edges.empty()) return;
      std::sort(long_edges.begin(), long_edges.end(), std::greater<>());
      for (const auto& entry : long_edges)
        if (edges_.count(entry.second)) bisect(entry.second);
    }
  }

  // Bisecting a long, thin input triangle leaves rows of points close to its long edges and
  // clusters near a fan's centre (a disk's cap), which no flip removes.
  void improve() {
    flip_all();
    for (int round = 0; round < 8; ++round) {
      const bool merged = merge_close_points() > 0;
      flip_all();
      smooth_points();
      flip_all();
      if (!merged && round >= 3) break;
    }
  }

 private:
  static std::pair<int, int> ends(std::int64_t key) {
    return {static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffff)};
  }
  V3 point(int v) const { return vec(s_.points_m[v]); }
  double length(int a, int b) const { return (point(a) - point(b)).norm(); }
  V3 normal(const std::array<int, 3>& f) const { return (point(f[1]) - point(f[0])).cross(point(f[2]) - point(f[0])); }

  void attach(int a, int b, int f) {
    auto [it, fresh] = edges_.try_emplace(undirected_edge_key(a, b), std::array<int, 2>{f, -1});
    if (!fresh) it->second[1] = f;
  }
  void replace(int a, int b, int old_f, int new_f) {
    auto& faces = edges_.at(undirected_edge_key(a, b));
    (faces[0] == old_f ? faces[0] : faces[1]) = new_f;
  }
  void remake_edges() {
    edges_.clear();
    for (std::size_t f = 0; f < s_.facets.size(); ++f)
      for (int k = 0; k < 3; ++k) attach(s_.facets[f][k], s_.facets[f][(k + 1) % 3], static_cast<int>(f));
  }
  // Facet f's corner index that starts edge (a, b), in either direction.
  int edge_index(int f, int a, int b) const {
    const auto& v = s_.facets[f];
    for (int k = 0; k < 3; ++k)
      if ((v[k] == a && v[(k + 1) % 3] == b) || (v[k] == b && v[(k + 1) % 3] == a)) return k;
    return -1;
  }

  // The facet's longest edge, ties broken by the key: a total order, so the recursion ends.
  std::int64_t longest(int f) const {
    std::pair<double, std::int64_t> best{-1, 0};
    for (int k = 0; k < 3; ++k) {
      const int a = s_.facets[f][k], b = s_.facets[f][(k + 1) % 3];
      best = std::max(best, {length(a, b), undirected_edge_key(a, b)});
    }
    return best.second;
  }

  void bisect(std::int64_t key) {
    for (int side = 0; side < 2; ++side)
      for (std::int64_t l = longest(edges_.at(key)[side]); l != key; l = longest(edges_.at(key)[side])) bisect(l);
    const auto [a, b] = ends(key);
    const std::array<int, 2> faces = edges_.at(key);
    edges_.erase(key);
    const int m = static_cast<int>(s_.points_m.size());
    int near = s_.near_triangle[faces[0]];
    const V3 chord = 0.5 * (point(a) + point(b));
    s_.points_m.push_back(projector_.project({chord(0), chord(1), chord(2)}, near));
    s_.size_m.push_back(0.5 * (s_.size_m[a] + s_.size_m[b]));
    if (s_.sharp_edges.erase(key)) s_.sharp_edges.insert({undirected_edge_key(a, m), undirected_edge_key(m, b)});
    for (int f : faces) split(f, a, b, m);
    if (static_cast<std::int64_t>(s_.facets.size()) > max_facets_)
      throw MeshError("object mesh", "the surface needs more than " + std::to_string(max_facets_) +
                                         " triangles at the sizes asked (edge length or thickness too small?)");
  }

  // Facet f = (p, q, c), (p, q) its (a, b) in order, becomes (p, m, c) and a new facet (m, q, c).
  void split(int f, int a, int b, int m) {
    const int k = edge_index(f, a, b);
    auto& v = s_.facets[f];
    const int p = v[k], q = v[(k + 1) % 3], c = v[(k + 2) % 3];
    std::array<int, 3> w = v;
    w[k] = m;
    v[(k + 1) % 3] = m;
    const int g = static_cast<int>(s_.facets.size());
    s_.facets.push_back(w);
    s_.near_triangle.push_back(s_.near_triangle[f]);
    replace(q, c, f, g);
    attach(p, m, f), attach(m, q, g), attach(m, c, f), attach(m, c, g);
  }

  // Flips the diagonal where the quadrilateral of its facets is not Delaunay (the angles opposite
  // it sum over pi), it is no sharp edge, and both new facets face as the old did.
  bool flip(std::int64_t key) {
    if (s_.sharp_edges.count(key)) return false;
    const auto [f, g] = edges_.at(key);
    const auto [a, b] = ends(key);
    const int k = edge_index(f, a, b);
    const int p = s_.facets[f][k], q = s_.facets[f][(k + 1) % 3], c = s_.facets[f][(k + 2) % 3];
    const auto& vg = s_.facets[g];
    const int d = vg[0] != p && vg[0] != q ? vg[0] : vg[1] != p && vg[1] != q ? vg[1] : vg[2];
    if (c == d || edges_.count(undirected_edge_key(c, d))) return false;
    auto angle = [&](int at, int u, int w) {
      const V3 x = point(u) - point(at), y = point(w) - point(at);
      return std::atan2(x.cross(y).norm(), x.dot(y));
    };
    if (!(angle(c, p, q) + angle(d, q, p) > std::numbers::pi * (1 + 1e-9))) return false;
    const V3 nf = normal(s_.facets[f]).normalized(), ng = normal(vg).normalized();
    // Convex seen along the mean normal: each diagonal separates the other's ends.
    const V3 n = nf + ng;
    auto side = [&](int from, int to, int x) { return (point(to) - point(from)).cross(point(x) - point(from)).dot(n); };
    if (!(side(p, q, c) * side(p, q, d) < 0) || !(side(c, d, p) * side(c, d, q) < 0)) return false;
    const std::array<int, 3> new_f{p, d, c}, new_g{d, q, c};
    for (const auto& m : {normal(new_f).normalized(), normal(new_g).normalized()})
      if (!(m.dot(nf) > 0.5) || !(m.dot(ng) > 0.5)) return false;
    s_.facets[f] = new_f, s_.facets[g] = new_g;
    edges_.erase(key);
    replace(q, c, f, g), replace(p, d, g, f);
    attach(c, d, f), attach(c, d, g);
    return true;
  }

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

  // Per point its facets, and whether it may move (on no sharp edge).
  void gather(std::vector<std::vector<int>>& around, std::vector<bool>& fixed) const {
    around.assign(s_.points_m.size(), {});
    for (std::size_t f = 0; f < s_.facets.size(); ++f)
      for (int v : s_.facets[f]) around[v].push_back(static_cast<int>(f));
    fixed.assign(s_.points_m.size(), false);
    for (std::int64_t key : s_.sharp_edges) fixed[ends(key).first] = fixed[ends(key).second] = true;
  }

  // The facets around a point keep their side (within 60 degrees of their old normals, a tenth
  // of their size's area at least unless already smaller); `changed` gives a facet's new corners.
  // Seen along the point's normal (their sum) they stay unfolded, a star about the point.
  template <class Changed>
  bool keeps_shape(const std::vector<int>& facets, const std::vector<V3>& old_normals, double size_m,
                   Changed changed) const {
    V3 star = V3::Zero();
    for (const V3& n : old_normals) star += n.normalized();
    star.normalize();
    for (std::size_t i = 0; i < facets.size(); ++i) {
      std::array<int, 3> w = s_.facets[facets[i]];
      if (!changed(w)) continue;
      const V3 n = normal(w);
      if (!(n.normalized().dot(old_normals[i].normalized()) > 0.5) || !(n.normalized().dot(star) > 0.2)) return false;
      if (!(n.norm() > std::min(0.1 * size_m * size_m, old_normals[i].norm()))) return false;
    }
    return true;
  }

  // Merging v into u keeps the surface manifold only if their common neighbours are the two
  // points across edge (v, u) (else two edges, or facets, become one).
  bool link_condition(int v, int u, const std::vector<std::vector<int>>& around) const {
    std::vector<int> of_v, of_u;
    for (int f : around[v])
      for (int w : s_.facets[f]) of_v.push_back(w);
    for (int f : around[u])
      for (int w : s_.facets[f]) of_u.push_back(w);
    for (auto* list : {&of_v, &of_u}) {
      std::sort(list->begin(), list->end());
      list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    std::vector<int> common;
    std::set_intersection(of_v.begin(), of_v.end(), of_u.begin(), of_u.end(), std::back_inserter(common));
    return common.size() == 4;  // v, u and the two across
  }

  int merge_close_points() {
    std::vector<std::vector<int>> around;
    std::vector<bool> fixed, touched(s_.points_m.size(), false), dead(s_.facets.size(), false);
    gather(around, fixed);
    int merged = 0;
    for (int v = 0; v < static_cast<int>(s_.points_m.size()); ++v) {
      if (fixed[v] || touched[v] || around[v].empty()) continue;
      std::vector<V3> old_normals;
      for (int f : around[v]) old_normals.push_back(normal(s_.facets[f]));
      std::vector<std::pair<double, int>> near;
      for (int f : around[v])
        for (int w : s_.facets[f])
          if (w != v && !touched[w] && length(v, w) < s_.size_m[v] / 3) near.push_back({length(v, w), w});
      std::sort(near.begin(), near.end());
      for (const auto& [d, u] : near) {
        auto onto_u = [&, u = u](std::array<int, 3>& w) {
          if (w[0] == u || w[1] == u || w[2] == u) return false;  // the two facets on edge (v, u) go
          for (int& x : w) x = x == v ? u : x;
          return true;
        };
        if (!link_condition(v, u, around) || !keeps_shape(around[v], old_normals, s_.size_m[v], onto_u)) continue;
        for (int f : around[v]) {
          for (int x : s_.facets[f]) touched[x] = true;
          if (!onto_u(s_.facets[f])) dead[f] = true;
        }
        ++merged;
        break;
      }
    }
    if (merged > 0) compact(dead);
    return merged;
  }

  // Drops the dead facets and the points on no facet (TetGen would take a point on a facet but
  // in none for an interior point).
  void compact(const std::vector<bool>& dead) {
    RefinedSurface kept;
    std::vector<int> index(s_.points_m.size(), -1);
    for (std::size_t f = 0; f < s_.facets.size(); ++f) {
      if (dead[f]) continue;
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
      kept.near_triangle.push_back(s_.near_triangle[f]);
    }
    for (std::int64_t key : s_.sharp_edges)
      kept.sharp_edges.insert(undirected_edge_key(index[ends(key).first], index[ends(key).second]));
    s_ = std::move(kept);
    remake_edges();
  }

  // Each free point to its neighbours' mean, projected onto the smooth surface, where the worst
  // facet around it does not get worse.
  void smooth_points() {
    std::vector<std::vector<int>> around;
    std::vector<bool> fixed;
    gather(around, fixed);
    for (int v = 0; v < static_cast<int>(s_.points_m.size()); ++v) {
      if (fixed[v] || around[v].empty()) continue;
      V3 sum = V3::Zero();
      std::vector<V3> old_normals;
      double before = std::numeric_limits<double>::infinity();
      for (int f : around[v]) {
        for (int w : s_.facets[f])
          if (w != v) sum += point(w);  // each neighbour twice: two facets share each edge out of v
        old_normals.push_back(normal(s_.facets[f]));
        before = std::min(before, old_normals.back().norm());
      }
      const P3 old = s_.points_m[v];
      int near = s_.near_triangle[around[v][0]];
      const V3 mean = sum / (2.0 * static_cast<double>(around[v].size()));
      s_.points_m[v] = projector_.project({mean(0), mean(1), mean(2)}, near);
      double after = std::numeric_limits<double>::infinity();
      for (int f : around[v]) after = std::min(after, normal(s_.facets[f]).norm());
      if (!(after >= before) ||
          !keeps_shape(around[v], old_normals, 0.0, [](const std::array<int, 3>&) { return true; }))
        s_.points_m[v] = old;
    }
  }

  RefinedSurface& s_;
  const SurfaceProjector& projector_;
  std::int64_t max_facets_;
  std::unordered_map<std::int64_t, std::array<int, 2>> edges_;
};

}  // namespace

RefinedSurface refine_surface(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                              const SurfaceProjector& projector, const std::vector<double>& vertex_size_m,
                              std::int64_t max_facets) {
  RefinedSurface s;
  s.points_m = vertices;
  s.size_m = vertex_size_m;
  s.facets = triangles;
  s.near_triangle.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    s.near_triangle[t] = static_cast<int>(t);
    for (int k = 0; k < 3; ++k)
      if (projector.surface().sharp(static_cast<int>(t), k))
        s.sharp_edges.insert(undirected_edge_key(triangles[t][k], triangles[t][(k + 1) % 3]));
  }
  Refinement refinement(s, projector, max_facets);
  refinement.bisect_all();
  refinement.improve();
  return s;
}

}  // namespace clatter::kernels::fem
