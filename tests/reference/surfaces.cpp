#include "tests/reference/surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace clatter::reference {
namespace {

using P3 = std::array<double, 3>;

P3 on_sphere(P3 p, double radius_m) {
  const double s = radius_m / std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return {p[0] * s, p[1] * s, p[2] * s};
}

// The boundary of a union of unit cells (integer coordinates, scaled by `size`): every cell face
// not shared with another cell, split into two triangles wound outward.
Surface cells_boundary(const std::set<std::array<int, 3>>& cells, const P3& size) {
  Surface s;
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](std::array<int, 3> g) {
    const auto [it, added] = index.try_emplace(g, static_cast<int>(s.vertices_m.size()));
    if (added) s.vertices_m.push_back({g[0] * size[0], g[1] * size[1], g[2] * size[2]});
    return it->second;
  };
  for (const auto& c : cells)
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        std::array<int, 3> n = c;
        n[static_cast<std::size_t>(axis)] += side ? 1 : -1;
        if (cells.count(n)) continue;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        std::array<std::array<int, 3>, 4> q;
        for (int k = 0; k < 4; ++k) {
          q[static_cast<std::size_t>(k)] = c;
          q[static_cast<std::size_t>(k)][static_cast<std::size_t>(axis)] += side;
          q[static_cast<std::size_t>(k)][static_cast<std::size_t>(u)] += (k == 1 || k == 2);
          q[static_cast<std::size_t>(k)][static_cast<std::size_t>(v)] += (k >= 2);
        }
        // (u, v, axis) is right-handed: u x v = +axis, so u-then-v is outward on the + side.
        const int a = vertex(q[0]), b = vertex(q[1]), cc = vertex(q[2]), d = vertex(q[3]);
        if (side)
          s.triangles.push_back({a, b, cc}), s.triangles.push_back({a, cc, d});
        else
          s.triangles.push_back({a, cc, b}), s.triangles.push_back({a, d, cc});
      }
  return s;
}

}  // namespace

Surface icosphere(double radius_m, int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  Surface s;
  for (const P3& p : std::vector<P3>{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                     {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}})
    s.vertices_m.push_back(on_sphere(p, radius_m));
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto found = mid.find({std::min(a, b), std::max(a, b)});
      if (found != mid.end()) return found->second;
      const P3 &p = s.vertices_m[static_cast<std::size_t>(a)], &q = s.vertices_m[static_cast<std::size_t>(b)];
      s.vertices_m.push_back(on_sphere({p[0] + q[0], p[1] + q[1], p[2] + q[2]}, radius_m));
      return mid[{std::min(a, b), std::max(a, b)}] = static_cast<int>(s.vertices_m.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& f : s.triangles) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    s.triangles = std::move(finer);
  }
  return s;
}

Surface ellipsoid_surface(const std::array<double, 3>& axes, int levels) {
  Surface s = icosphere(1.0, levels);
  for (auto& p : s.vertices_m)
    for (std::size_t i = 0; i < 3; ++i) p[i] *= axes[i];
  return s;
}

Surface box(double a_m, double b_m, double c_m, int n) {
  std::set<std::array<int, 3>> cells;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) cells.insert({i, j, k});
  return cells_boundary(cells, {a_m / n, b_m / n, c_m / n});
}

Surface l_prism(double w_m, double h_m) { return cells_boundary({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {w_m, w_m, h_m}); }

Surface scaled(Surface s, double factor) {
  for (auto& p : s.vertices_m)
    for (double& c : p) c *= factor;
  return s;
}

}  // namespace clatter::reference
