// The surface triangulation of an ellipsoid handed to TetGen (no TetGen here).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/fem/ellipsoid_parts.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

constexpr double kOctahedronPerimeterRatio = 2.5;
// Edges above this times h are cut too (a cigar's octahedron is coarse along its axis); above the
// longest edges of the smoothed octahedron, which are kept.
constexpr double kEdgeAboveH = 1.5;

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

// Outward: the face normal along the ellipsoid's gradient at the centroid (the centroid's own
// direction is almost tangent near the rim of a flat ellipsoid).
void orient_outward(SurfaceTriangulation& s, const P3& r) {
  for (auto& f : s.faces) {
    const P3 &a = s.vertices_m[f[0]], &b = s.vertices_m[f[1]], &c = s.vertices_m[f[2]];
    const P3 gradient{(a[0] + b[0] + c[0]) / (r[0] * r[0]), (a[1] + b[1] + c[1]) / (r[1] * r[1]),
                      (a[2] + b[2] + c[2]) / (r[2] * r[2])};
    if (dot(cross(sub(b, a), sub(c, a)), gradient) < 0) std::swap(f[1], f[2]);
  }
}

// Ramanujan's second approximation (exact for a circle, 0.4 % off for a segment).
double ellipse_perimeter_m(double a, double b) {
  const double l = 3 * std::pow((a - b) / (a + b), 2);
  return std::numbers::pi * (a + b) * (1 + l / (10 + std::sqrt(4 - l)));
}

std::vector<std::vector<int>> neighbours_of(const SurfaceTriangulation& s) {
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
  return neighbours;
}

// Jacobi Laplacian smoothing, each vertex put back on the ellipsoid along its ray from the
// centre: the linear map of a sphere crowds the rim of a flat ellipsoid with needle triangles
// (spacing c/a of the faces'); moving each vertex towards its neighbours' centroid evens out the
// spacing along the surface. (The symmetric octahedron's: its collapse mode is never excited.)
void smooth_on_surface(SurfaceTriangulation& s, const P3& r, int iterations) {
  const auto neighbours = neighbours_of(s);
  std::vector<P3> next(s.vertices_m.size());
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t v = 0; v < neighbours.size(); ++v) {
      P3 c{0, 0, 0};
      for (int w : neighbours[v])
        for (int k = 0; k < 3; ++k) c[k] += s.vertices_m[w][k];
      // A vertex on a coordinate plane stays on it exactly (by symmetry it would, up to rounding):
      // the principal ellipses stay polylines (surface_improve.cpp).
      for (int k = 0; k < 3; ++k)
        if (s.vertices_m[v][k] == 0) c[k] = 0;
      next[v] = onto_ellipsoid(r, c);
    }
    s.vertices_m.swap(next);
  }
}

// The base's points (directions from the centre) on the ellipsoid.
SurfaceTriangulation on_ellipsoid(SurfaceTriangulation s, const P3& r) {
  for (auto& v : s.vertices_m) {
    const double norm = std::sqrt(dot(v, v));
    v = {r[0] * v[0] / norm, r[1] * v[1] / norm, r[2] * v[2] / norm};
  }
  return s;
}

}  // namespace

P3 onto_ellipsoid(const P3& r, const P3& p) {
  const double q = std::sqrt((p[0] / r[0]) * (p[0] / r[0]) + (p[1] / r[1]) * (p[1] / r[1]) +
                             (p[2] / r[2]) * (p[2] / r[2]));
  return {p[0] / q, p[1] / q, p[2] / q};
}

P3 nearest_on_ellipsoid(const P3& r, const P3& p) {
  if (r[0] == r[1] && r[1] == r[2]) return onto_ellipsoid(r, p);  // the same point, and the old sphere meshes
  // The nearest point is x_i = p_i r_i^2 / (r_i^2 + t) with g(t) = sum (p_i r_i / (r_i^2 + t))^2 - 1
  // = 0. g is convex and decreasing for t > -min r_i^2, so Newton from a t with g(t) >= 0 climbs
  // to the root without overshooting.
  auto g = [&](double t, double* slope) {
    double value = -1, derivative = 0;
    for (int i = 0; i < 3; ++i) {
      const double q = p[i] * r[i] / (r[i] * r[i] + t);
      value += q * q;
      derivative -= 2 * q * q / (r[i] * r[i] + t);
    }
    if (slope) *slope = derivative;
    return value;
  };
  // The pole: the smallest r_i^2 with p_i != 0 (a zero p_i drops out of g).
  double floor = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
    if (p[i] != 0) floor = std::max(floor, -r[i] * r[i]);
  double t = 0;
  for (int halving = 1; g(t, nullptr) < 0; ++halving) {
    if (halving > 60) return onto_ellipsoid(r, p);
    t = floor * (1 - std::ldexp(1.0, -halving));
  }
  for (int it = 0; it < 100; ++it) {
    double slope = 0;
    const double value = g(t, &slope);
    const double next = t - value / slope;
    if (!(next > t)) break;
    t = next;
  }
  // Past a pole of an axis p has no part along, p is deeper than the curvature radius there
  // (on a cigar's axis, beyond its tip's centre of curvature): the stationary point found is not
  // the nearest, and such a point only comes from a coarse chord; the ray from the centre then.
  if (t <= -std::min({r[0] * r[0], r[1] * r[1], r[2] * r[2]})) return onto_ellipsoid(r, p);
  return onto_ellipsoid(r, {p[0] * r[0] * r[0] / (r[0] * r[0] + t), p[1] * r[1] * r[1] / (r[1] * r[1] + t),
                            p[2] * r[2] * r[2] / (r[2] * r[2] + t)});
}

EdgeRule surface_rule(const P3& r, double h, double k) { return {r, kEdgeAboveH * h, k}; }

SurfaceTriangulation ellipsoid_surface(const P3& r, double h, double k) {
  if (!(r[0] > 0 && r[1] > 0 && r[2] > 0 && h > 0 && k > 0))
    throw std::invalid_argument("ellipsoid_surface: semi-axes, edge length and k must be positive");
  // The octahedron's three great circles carry 4 n edges each. Where their perimeters differ by
  // up to kOctahedronPerimeterRatio, n from the area and Laplacian smoothing even out the spacing
  // (flat ellipsoids). Beyond, the triangles would be as anisotropic as the perimeters, finer
  // than h around the shortest (a cigar's waist), and smoothing cannot move vertices from one
  // great circle to another: n from the shortest perimeter instead (edges about h there), and the
  // longer ones cut down to h by the bisection below.
  double perimeters[3] = {ellipse_perimeter_m(r[1], r[2]), ellipse_perimeter_m(r[2], r[0]), ellipse_perimeter_m(r[0], r[1])};
  std::sort(perimeters, perimeters + 3);
  SurfaceTriangulation s;
  if (perimeters[2] <= kOctahedronPerimeterRatio * perimeters[0]) {
    // 8 n^2 equilateral triangles of edge h cover the area 2 sqrt(3) n^2 h^2.
    const int n = std::max(2, static_cast<int>(std::ceil(std::sqrt(surface_area_m2(r) / (2 * std::sqrt(3.0) * h * h)))));
    s = on_ellipsoid(subdivided_octahedron(n), r);
    // Spacing diffuses over the n-vertex-long paths in about n^2 sweeps.
    smooth_on_surface(s, r, 2 * n * n);
  } else {
    s = on_ellipsoid(subdivided_octahedron(std::max(1, static_cast<int>(std::lround(perimeters[0] / (4 * h))))), r);
  }
  orient_outward(s, r);
  const EdgeRule rule = surface_rule(r, h, k);
  refine_surface(s, rule);
  improve_surface(s, rule);
  // The flips may leave an edge too coarse (they trade it for angles): cut again, a few rounds.
  for (int round = 0; round < 3 && refine_surface(s, rule); ++round) improve_surface(s, rule);
  return s;
}

}  // namespace clatter::kernels::fem
