#include "tests/reference/test_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace clatter::reference {

namespace {
// Turns every triangle outward; for convex meshes around the origin: a triangle's normal must
// point away from the origin, as its centroid does.
Mesh outward(Mesh m) {
  for (auto& t : m.triangles) {
    const auto& a = m.vertices[static_cast<std::size_t>(t[0])];
    const auto& b = m.vertices[static_cast<std::size_t>(t[1])];
    const auto& c = m.vertices[static_cast<std::size_t>(t[2])];
    const std::array<double, 3> e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2]) < 0) std::swap(t[1], t[2]);
  }
  return m;
}
}  // namespace

Mesh box_mesh(double hx, double hy, double hz) {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.vertices.push_back({i & 1 ? hx : -hx, i & 2 ? hy : -hy, i & 4 ? hz : -hz});
  // Faces as quads (outward after `outward`), each split along one diagonal.
  const int quads[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return outward(std::move(m));
}

Mesh icosphere(double radius, int levels, double sx, double sy, double sz) {
  const double p = (1 + std::sqrt(5.0)) / 2;
  Mesh m;
  m.vertices = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto unit = [](std::array<double, 3> v) {
    const double r = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return std::array<double, 3>{v[0] / r, v[1] / r, v[2] / r};
  };
  for (auto& v : m.vertices) v = unit(v);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      const auto& va = m.vertices[static_cast<std::size_t>(a)];
      const auto& vb = m.vertices[static_cast<std::size_t>(b)];
      m.vertices.push_back(unit({va[0] + vb[0], va[1] + vb[1], va[2] + vb[2]}));
      return middle[key] = static_cast<int>(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : m.triangles) {
      const int a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      next.push_back({t[0], a, c});
      next.push_back({t[1], b, a});
      next.push_back({t[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = std::move(next);
  }
  for (auto& v : m.vertices) v = {radius * sx * v[0], radius * sy * v[1], radius * sz * v[2]};
  return outward(std::move(m));
}

Mesh cut_cube(double h, double cut) {
  // The box's vertices except (h, h, h), which becomes the three points of the cut plane on its
  // edges; the three faces at that corner become pentagons (fans), and the cut a triangle.
  Mesh m;
  for (int i = 0; i < 7; ++i) m.vertices.push_back({i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h});
  m.vertices.push_back({h - cut, h, h});  // 7: on the edge towards -x
  m.vertices.push_back({h, h - cut, h});  // 8: towards -y
  m.vertices.push_back({h, h, h - cut});  // 9: towards -z
  auto fan = [&](std::vector<int> poly) {
    for (std::size_t k = 1; k + 1 < poly.size(); ++k) m.triangles.push_back({poly[0], poly[k], poly[k + 1]});
  };
  fan({0, 2, 6, 4});        // -x
  fan({1, 3, 9, 8, 5});     // +x: 1 (h,-h,-h), 3 (h,h,-h), 9, 8, 5 (h,-h,h)
  fan({0, 4, 5, 1});        // -y
  fan({2, 6, 7, 9, 3});     // +y
  fan({0, 1, 3, 2});        // -z
  fan({4, 6, 7, 8, 5});     // +z
  m.triangles.push_back({7, 8, 9});  // the cut, normal (1, 1, 1)
  return outward(std::move(m));
}

Mesh square_pyramid(double half_base, double height) {
  Mesh m;
  const double base = -height / 4;
  m.vertices = {{-half_base, -half_base, base}, {half_base, -half_base, base}, {half_base, half_base, base},
                {-half_base, half_base, base}, {0, 0, 3 * height / 4}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  return outward(std::move(m));
}

Section mesh_section(const Mesh& mesh, int axis, double at) {
  const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
  Section s;
  for (const auto& t : mesh.triangles) {
    std::array<std::array<double, 3>, 3> p{};
    for (int k = 0; k < 3; ++k) p[k] = mesh.vertices[static_cast<std::size_t>(t[k])];
    std::vector<std::array<double, 3>> cross;
    for (int k = 0; k < 3; ++k) {
      const auto& a = p[k];
      const auto& b = p[(k + 1) % 3];
      const double da = a[axis] - at, db = b[axis] - at;
      if (da == 0 || db == 0) throw std::invalid_argument("mesh_section: a vertex lies on the plane");
      if ((da < 0) == (db < 0)) continue;
      const double f = da / (da - db);
      cross.push_back({a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])});
    }
    if (cross.size() != 2) continue;
    // Orient the segment counter-clockwise in the (u, v) plane: the section's outward normal there is
    // (n_u, n_v), and the counter-clockwise tangent is that turned by +90 degrees.
    const std::array<double, 3> e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const std::array<double, 3> e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double tu = -n[v], tv = n[u];
    auto P = cross[0], Q = cross[1];
    if ((Q[u] - P[u]) * tu + (Q[v] - P[v]) * tv < 0) std::swap(P, Q);
    const double w = P[u] * Q[v] - Q[u] * P[v];  // twice the signed area of (0, P, Q)
    s.area += w / 2;
    s.moment[u] += (P[u] + Q[u]) * w / 6;
    s.moment[v] += (P[v] + Q[v]) * w / 6;
  }
  s.moment[axis] = at * s.area;
  return s;
}

}  // namespace clatter::reference
