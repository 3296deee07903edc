#include "kernels/pan/directions.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace clatter::kernels::pan {
namespace {
int vertex_index(int a, int b) {
  // Row a holds b = 0 .. 8 - a; rows before a hold sum_{r < a} (9 - r) vertices.
  return a * (kDivisions + 1) - a * (a - 1) / 2 + b;
}
}  // namespace

const std::vector<std::array<double, 3>>& direction_vertices() {
  static const std::vector<std::array<double, 3>> v = [] {
    std::vector<std::array<double, 3>> out;
    for (int a = 0; a <= kDivisions; ++a)
      for (int b = 0; a + b <= kDivisions; ++b) {
        const double x = a, y = b, z = kDivisions - a - b, n = std::sqrt(x * x + y * y + z * z);
        out.push_back({x / n, y / n, z / n});
      }
    return out;
  }();
  return v;
}

const std::vector<std::array<int, 3>>& direction_triangles() {
  static const std::vector<std::array<int, 3>> t = [] {
    std::vector<std::array<int, 3>> out;
    for (int a = 0; a < kDivisions; ++a)
      for (int b = 0; a + b < kDivisions; ++b) {
        out.push_back({vertex_index(a, b), vertex_index(a + 1, b), vertex_index(a, b + 1)});
        if (a + b + 1 < kDivisions)
          out.push_back({vertex_index(a + 1, b), vertex_index(a, b + 1), vertex_index(a + 1, b + 1)});
      }
    return out;
  }();
  return t;
}

DirectionWeights locate_direction(const std::array<double, 3>& d) {
  const double s = d[0] + d[1] + d[2];
  if (!(s > 0) || d[0] < 0 || d[1] < 0 || d[2] < 0)
    throw std::invalid_argument("locate_direction: direction outside the positive octant");
  const double ua = kDivisions * d[0] / s, ub = kDivisions * d[1] / s;
  int a = std::min(static_cast<int>(std::floor(ua)), kDivisions);
  int b = std::min(static_cast<int>(std::floor(ub)), kDivisions - a);
  double fa = ua - a, fb = ub - b;
  DirectionWeights w;
  if (a + b == kDivisions) {  // on the far edge: the vertex itself
    w.vertex = {vertex_index(a, b), vertex_index(a, b), vertex_index(a, b)};
    w.weight = {1.0, 0.0, 0.0};
    return w;
  }
  if (fa + fb <= 1.0) {
    w.vertex = {vertex_index(a, b), vertex_index(a + 1, b), vertex_index(a, b + 1)};
    w.weight = {1.0 - fa - fb, fa, fb};
  } else {
    w.vertex = {vertex_index(a + 1, b + 1), vertex_index(a + 1, b), vertex_index(a, b + 1)};
    w.weight = {fa + fb - 1.0, 1.0 - fb, 1.0 - fa};
  }
  for (double& x : w.weight) x = std::max(x, 0.0);
  return w;
}

}  // namespace clatter::kernels::pan
