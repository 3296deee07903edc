// The surface triangulation of an ellipsoid handed to TetGen (no TetGen here).
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "kernels/fem/ellipsoid_mesh.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Thomsen's approximation (p = 1.6075, within 1.1 %): only the number of subdivisions depends on it.
double surface_area_m2(const P3& r) {
  const double p = 1.6075;
  const double ap = std::pow(r[0], p), bp = std::pow(r[1], p), cp = std::pow(r[2], p);
  return 4 * std::numbers::pi * std::pow((ap * bp + ap * cp + bp * cp) / 3, 1 / p);
}

// The octahedron |x| + |y| + |z| = n with each face cut into n^2 triangles, on integer points;
// a std::map keyed by the integer point shares the vertices of neighbouring faces in a fixed order.
SurfaceTriangulation subdivided_octahedron(int n) {
  SurfaceTriangulation s;
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](int x, int y, int z) {
    const auto [it, inserted] = index.try_emplace({x, y, z}, static_cast<int>(s.vertices_m.size()));
    if (inserted) s.vertices_m.push_back({double(x), double(y), double(z)});
    return it->second;
  };
  for (int octant = 0; octant < 8; ++octant) {
    const int sx = octant & 1 ? -1 : 1, sy = octant & 2 ? -1 : 1, sz = octant & 4 ? -1 : 1;
    auto at = [&](int i, int j) { return vertex(sx * i, sy * j, sz * (n - i - j)); };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        s.faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 2 <= n) s.faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  return s;
}

void orient_outward(SurfaceTriangulation& s) {
  for (auto& f : s.faces) {
    const P3 &a = s.vertices_m[f[0]], &b = s.vertices_m[f[1]], &c = s.vertices_m[f[2]];
    const P3 centroid{a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
    if (dot(cross(sub(b, a), sub(c, a)), centroid) < 0) std::swap(f[1], f[2]);
  }
}

// Jacobi Laplacian smoothing, each vertex put back on the ellipsoid: the linear map of a sphere
// crowds the rim of a flat ellipsoid with needle triangles (spacing c/a of the faces'); moving each
// vertex towards its neighbours' centroid evens out the spacing along the surface.
void smooth_on_surface(SurfaceTriangulation& s, const P3& r, int iterations) {
  std::vector<std::vector<int>> neighbours(s.vertices_m.size());
  for (const auto& f : s.faces)
    for (int k = 0; k < 3; ++k) {
      neighbours[f[k]].push_back(f[(k + 1) % 3]);
      neighbours[f[k]].push_back(f[(k + 2) % 3]);
    }
  for (auto& n : neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  std::vector<P3> next(s.vertices_m.size());
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t v = 0; v < neighbours.size(); ++v) {
      P3 c{0, 0, 0};
      for (int w : neighbours[v])
        for (int k = 0; k < 3; ++k) c[k] += s.vertices_m[w][k];
      next[v] = onto_ellipsoid(r, c);
    }
    s.vertices_m.swap(next);
  }
}

}  // namespace

P3 onto_ellipsoid(const P3& r, const P3& p) {
  const double q = std::sqrt((p[0] / r[0]) * (p[0] / r[0]) + (p[1] / r[1]) * (p[1] / r[1]) +
                             (p[2] / r[2]) * (p[2] / r[2]));
  return {p[0] / q, p[1] / q, p[2] / q};
}

SurfaceTriangulation ellipsoid_surface(const P3& r, double h) {
  if (!(r[0] > 0 && r[1] > 0 && r[2] > 0 && h > 0))
    throw std::invalid_argument("ellipsoid_surface: semi-axes and edge length must be positive");
  // 8 n^2 equilateral triangles of edge h cover the area 2 sqrt(3) n^2 h^2.
  const int n = std::max(2, static_cast<int>(std::ceil(std::sqrt(surface_area_m2(r) / (2 * std::sqrt(3.0) * h * h)))));
  SurfaceTriangulation s = subdivided_octahedron(n);
  for (auto& v : s.vertices_m) {
    const double norm = std::sqrt(dot(v, v));
    v = {r[0] * v[0] / norm, r[1] * v[1] / norm, r[2] * v[2] / norm};
  }
  // Spacing diffuses over the n-vertex-long paths in about n^2 sweeps.
  smooth_on_surface(s, r, 2 * n * n);
  orient_outward(s);
  return s;
}

}  // namespace clatter::kernels::fem
