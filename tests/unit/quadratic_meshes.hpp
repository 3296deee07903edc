#pragma once
// Curved 6-node surface meshes (3 corners counter-clockwise from outside, then the mid-nodes of
// edges 01, 12, 20, as model::ModalEntry stores them) made from the flat meshes of
// test_meshes.hpp: every triangle split into 4 `refine` times, new nodes put on the exact
// surface by `project`; and a plate (a flat disk with a cylindrical rim) meshed in rings.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <numbers>
#include <vector>

#include "tests/unit/test_meshes.hpp"

namespace clatter::test {

struct QuadraticSurface {
  std::vector<std::array<double, 3>> nodes_m;
  std::vector<std::array<std::int32_t, 6>> faces;
};

// p on the exact surface, given the edge's two end nodes it was made from (a mid-point).
using Projection = std::function<std::array<double, 3>(const std::array<double, 3>& mid,
                                                       const std::array<double, 3>& a, const std::array<double, 3>& b)>;

inline std::array<double, 3> flat(const std::array<double, 3>& mid, const std::array<double, 3>&, const std::array<double, 3>&) {
  return mid;
}

inline QuadraticSurface quadratic_surface(io::TriangleMesh m, int refine, const Projection& project) {
  auto midpoint = [&](int a, int b) {
    const auto& p = m.vertices_m[static_cast<std::size_t>(a)];
    const auto& q = m.vertices_m[static_cast<std::size_t>(b)];
    return project({(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2}, p, q);
  };
  for (int level = 0; level < refine; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      m.vertices_m.push_back(midpoint(a, b));
      return middle[key] = static_cast<int>(m.vertices_m.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : m.triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    m.triangles = std::move(next);
  }
  QuadraticSurface s;
  s.nodes_m = m.vertices_m;
  std::map<std::pair<int, int>, int> middle;
  auto mid = [&](int a, int b) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    const auto it = middle.find(key);
    if (it != middle.end()) return it->second;
    s.nodes_m.push_back(midpoint(a, b));
    return middle[key] = static_cast<int>(s.nodes_m.size()) - 1;
  };
  for (const auto& t : m.triangles) s.faces.push_back({t[0], t[1], t[2], mid(t[0], t[1]), mid(t[1], t[2]), mid(t[2], t[0])});
  return s;
}

inline Projection onto_sphere(double radius_m) {
  return [radius_m](const std::array<double, 3>& p, const std::array<double, 3>&, const std::array<double, 3>&) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{radius_m * p[0] / n, radius_m * p[1] / n, radius_m * p[2] / n};
  };
}

// The cylinder's side (radius about z): a mid-point of an edge whose two ends are on it goes
// radially onto it (side edges and rim edges); other edges stay straight.
inline Projection onto_cylinder(double radius_m) {
  return [radius_m](const std::array<double, 3>& p, const std::array<double, 3>& a, const std::array<double, 3>& b) {
    auto on_side = [&](const std::array<double, 3>& q) { return std::abs(std::hypot(q[0], q[1]) - radius_m) < 1e-9 * radius_m; };
    if (!on_side(a) || !on_side(b)) return p;
    const double r = std::hypot(p[0], p[1]);
    return std::array<double, 3>{radius_m * p[0] / r, radius_m * p[1] / r, p[2]};
  };
}

// A disk of radius_m and thickness_m centred at the origin (faces z = +-thickness / 2): each face
// `rings` rings of 6j nodes (about radius / rings apart), the rim one band; mid-nodes of rim and
// side edges on the cylinder.
inline QuadraticSurface plate(double radius_m, double thickness_m, int rings) {
  io::TriangleMesh m;
  std::array<std::vector<std::vector<int>>, 2> ring;  // [face][j] node ids
  for (int side = 0; side < 2; ++side) {
    const double z = side == 0 ? -thickness_m / 2 : thickness_m / 2;
    ring[side].resize(static_cast<std::size_t>(rings) + 1);
    m.vertices_m.push_back({0, 0, z});
    ring[side][0] = {static_cast<int>(m.vertices_m.size()) - 1};
    for (int j = 1; j <= rings; ++j)
      for (int i = 0; i < 6 * j; ++i) {
        const double a = 2 * std::numbers::pi * i / (6 * j), r = radius_m * j / rings;
        m.vertices_m.push_back({r * std::cos(a), r * std::sin(a), z});
        ring[side][static_cast<std::size_t>(j)].push_back(static_cast<int>(m.vertices_m.size()) - 1);
      }
  }
  auto add = [&](int a, int b, int c, const Eigen::Vector3d& outward) {
    const auto& p = m.vertices_m;
    const Eigen::Vector3d x0(p[a][0], p[a][1], p[a][2]), x1(p[b][0], p[b][1], p[b][2]), x2(p[c][0], p[c][1], p[c][2]);
    if ((x1 - x0).cross(x2 - x0).dot(outward) < 0) std::swap(b, c);
    m.triangles.push_back({a, b, c});
  };
  for (int side = 0; side < 2; ++side) {
    const Eigen::Vector3d out(0, 0, side == 0 ? -1 : 1);
    for (int j = 1; j <= rings; ++j) {
      const auto& in = ring[side][static_cast<std::size_t>(j - 1)];
      const auto& ou = ring[side][static_cast<std::size_t>(j)];
      if (j == 1) {
        for (std::size_t b = 0; b < ou.size(); ++b) add(in[0], ou[b], ou[(b + 1) % ou.size()], out);
        continue;
      }
      // Walk both rings by angle, each step a triangle on the ring that is behind.
      std::size_t a = 0, b = 0;
      const std::size_t na = in.size(), nb = ou.size();
      while (a < na || b < nb) {
        if (b < nb && (a == na || double(b + 1) / double(nb) <= double(a + 1) / double(na))) {
          add(in[a % na], ou[b], ou[(b + 1) % nb], out);
          ++b;
        } else {
          add(in[a], in[(a + 1) % na], ou[b % nb], out);
          ++a;
        }
      }
    }
  }
  const auto& lo = ring[0][static_cast<std::size_t>(rings)];
  const auto& hi = ring[1][static_cast<std::size_t>(rings)];
  for (std::size_t i = 0; i < lo.size(); ++i) {
    const std::size_t n = (i + 1) % lo.size();
    const double a = 2 * std::numbers::pi * (double(i) + 0.5) / double(lo.size());
    const Eigen::Vector3d out(std::cos(a), std::sin(a), 0);
    add(lo[i], lo[n], hi[n], out);
    add(lo[i], hi[n], hi[i], out);
  }
  return quadratic_surface(m, 0, onto_cylinder(radius_m));
}

}  // namespace clatter::test
