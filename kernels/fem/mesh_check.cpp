#include "kernels/fem/mesh_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <unordered_map>

#include "kernels/fem/tetgen_fill.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

std::int64_t edge_key(int a, int b) { return static_cast<std::int64_t>(a) << 32 | static_cast<std::uint32_t>(b); }

std::string edge_name(int a, int b) {
  char name[48];
  std::snprintf(name, sizeof name, "(%d, %d)", a, b);
  return name;
}

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const P3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

double box_diagonal_m(const std::vector<P3>& vertices) {
  P3 lo{vertices.front()}, hi{vertices.front()};
  for (const P3& v : vertices)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]);
  return norm(sub(hi, lo));
}

// 6 times the signed volume of the cone from the origin over triangle f.
double six_volume(const std::vector<P3>& v, const std::array<int, 3>& f) {
  const P3 &a = v[f[0]], &b = v[f[1]], &c = v[f[2]];
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// Triangles joined across edges: the surface's connected parts, as a root per triangle.
std::vector<int> surface_parts(const std::vector<std::array<int, 3>>& triangles) {
  std::vector<int> parent(triangles.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  std::unordered_map<std::int64_t, int> first;  // undirected edge -> a triangle on it
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      const auto [it, fresh] = first.try_emplace(edge_key(std::min(a, b), std::max(a, b)), static_cast<int>(t));
      if (!fresh) parent[root(static_cast<int>(t))] = root(it->second);
    }
  for (std::size_t t = 0; t < triangles.size(); ++t) parent[t] = root(static_cast<int>(t));
  return parent;
}

}  // namespace

std::string surface_topology_problem(const std::vector<P3>& vertices,
                                     const std::vector<std::array<int, 3>>& triangles) {
  if (triangles.size() < 4)
    return "the surface has " + std::to_string(triangles.size()) + " triangles; a closed one needs 4";
  for (std::size_t v = 0; v < vertices.size(); ++v)
    for (double c : vertices[v])
      if (!std::isfinite(c)) return "vertex " + std::to_string(v) + " has a coordinate that is not finite";
  const int n = static_cast<int>(vertices.size());
  std::unordered_map<std::int64_t, int> directed;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& f = triangles[t];
    for (int k = 0; k < 3; ++k)
      if (f[k] < 0 || f[k] >= n)
        return "triangle " + std::to_string(t) + " names vertex " + std::to_string(f[k]) + " of " + std::to_string(n);
    if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) return "triangle " + std::to_string(t) + " repeats a vertex";
    for (int k = 0; k < 3; ++k) ++directed[edge_key(f[k], f[(k + 1) % 3])];
  }
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      const auto back = directed.find(edge_key(b, a));
      const int forward = directed[edge_key(a, b)], backward = back == directed.end() ? 0 : back->second;
      const std::string where = "edge " + edge_name(a, b) + " of triangle " + std::to_string(t);
      if (forward + backward == 1) return "the surface is open: " + where + " bounds one triangle only";
      if (forward + backward > 2)
        return "the surface is not manifold: " + where + " bounds " + std::to_string(forward + backward) + " triangles";
      if (forward != 1)
        return "the triangles are not consistently oriented at " + where + " (two run along it the same way)";
    }
  return "";
}

std::string degenerate_triangle_problem(const std::vector<P3>& vertices,
                                        const std::vector<std::array<int, 3>>& triangles, double relative_height) {
  const double floor_m = relative_height * box_diagonal_m(vertices);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& f = triangles[t];
    double longest = 0;
    for (int k = 0; k < 3; ++k) longest = std::max(longest, norm(sub(vertices[f[(k + 1) % 3]], vertices[f[k]])));
    const double twice_area = norm(cross(sub(vertices[f[1]], vertices[f[0]]), sub(vertices[f[2]], vertices[f[0]])));
    if (!(twice_area > floor_m * longest)) {
      char reason[200];
      std::snprintf(reason, sizeof reason,
                    "triangle %zu (vertices %d, %d, %d) is degenerate: area %.3g m^2, height %.3g m", t, f[0], f[1],
                    f[2], 0.5 * twice_area, longest > 0 ? twice_area / longest : 0.0);
      return reason;
    }
  }
  return "";
}

std::string self_intersection_problem(const std::vector<P3>& vertices,
                                      const std::vector<std::array<int, 3>>& triangles) {
  // TetGen tetrahedralizes every point it is given: only the used ones go in.
  std::vector<int> index(vertices.size(), -1), input;
  std::vector<P3> used;
  std::vector<std::array<int, 3>> facets;
  facets.reserve(triangles.size());
  for (const auto& f : triangles) {
    std::array<int, 3> g{};
    for (int k = 0; k < 3; ++k) {
      if (index[f[k]] < 0)
        index[f[k]] = static_cast<int>(used.size()), used.push_back(vertices[f[k]]), input.push_back(f[k]);
      g[k] = index[f[k]];
    }
    facets.push_back(g);
  }
  const TetgenFill found = tetgen_fill(used, facets, "", true);
  if (found.intersecting_faces == 0) {
    if (found.failure_code == 0) return "";
    return "TetGen's intersection test failed (code " + std::to_string(found.failure_code) +
           "): triangles that overlap or repeat?";
  }
  // Name the first crossing triangle by its index in the input.
  std::array<int, 3> first = found.faces.front();
  for (int& v : first) v = input[v];
  std::sort(first.begin(), first.end());
  std::size_t t = 0;
  for (; t < triangles.size(); ++t) {
    std::array<int, 3> f = triangles[t];
    std::sort(f.begin(), f.end());
    if (f == first) break;
  }
  char reason[200];
  std::snprintf(
      reason, sizeof reason,
      "the surface intersects itself: %d triangles cross another, triangle %zu (vertices %d, %d, %d) among them",
      found.intersecting_faces, t, first[0], first[1], first[2]);
  return reason;
}

double check_object_surface(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  if (std::string problem = surface_topology_problem(vertices, triangles); !problem.empty())
    throw SurfaceError(problem);
  if (std::string problem = degenerate_triangle_problem(vertices, triangles); !problem.empty())
    throw SurfaceError(problem);
  const std::vector<int> part = surface_parts(triangles);
  std::unordered_map<int, double> six_volume_of;
  std::vector<int> roots;  // in order of first triangle: deterministic messages
  double six_total = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const double s = six_volume(vertices, triangles[t]);
    if (six_volume_of.try_emplace(part[t], 0.0).second) roots.push_back(part[t]);
    six_volume_of[part[t]] += s;
    six_total += s;
  }
  char reason[240];
  if (!(six_total > 0)) {
    std::snprintf(reason, sizeof reason,
                  "the faces point inward: the enclosed volume is %.6g m^3 (triangles clockwise seen "
                  "from outside; reverse their winding)",
                  six_total / 6);
    throw SurfaceError(reason);
  }
  // Crossing first: two overlapping bodies are told by the crossing, the truer reason.
  const std::string crossing = self_intersection_problem(vertices, triangles);
  if (!crossing.empty()) throw SurfaceError(crossing);
  int bodies = 0;
  for (int r : roots) bodies += six_volume_of[r] > 0;
  if (bodies > 1) {
    std::snprintf(reason, sizeof reason,
                  "the surface has %d separate parts that each enclose a solid (the one with triangle 0 "
                  "among them): one object is one solid",
                  bodies);
    throw SurfaceError(reason);
  }
  return six_total / 6;
}

std::vector<int> cavity_triangles(const std::vector<P3>& vertices, const std::vector<std::array<int, 3>>& triangles) {
  const std::vector<int> part = surface_parts(triangles);
  std::unordered_map<int, double> six_volume_of;
  std::vector<int> first;  // each part's first triangle
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (six_volume_of.try_emplace(part[t], 0.0).second) first.push_back(static_cast<int>(t));
    six_volume_of[part[t]] += six_volume(vertices, triangles[t]);
  }
  std::vector<int> out;
  for (int t : first)
    if (six_volume_of[part[t]] < 0) out.push_back(t);
  return out;
}

std::string implausible_scale(const std::vector<P3>& vertices, double volume_m3, double rho_kg_m3,
                              const ScaleLimits& limits) {
  const double size_m = vertices.empty() ? 0 : box_diagonal_m(vertices), mass_kg = volume_m3 * rho_kg_m3;
  if (!(size_m > limits.max_size_m) && !(mass_kg > limits.max_mass_kg)) return "";
  char reason[300];
  std::snprintf(reason, sizeof reason,
                "the object is %.3g m across (bounding-box diagonal) and weighs %.3g kg at %.4g kg/m^3, "
                "over the plausible %.3g m or %.3g kg: is the mesh in millimetres rather than metres?",
                size_m, mass_kg, rho_kg_m3, limits.max_size_m, limits.max_mass_kg);
  return reason;
}

}  // namespace clatter::kernels::fem
