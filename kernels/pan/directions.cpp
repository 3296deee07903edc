#include "kernels/pan/directions.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace clatter::kernels::pan {
namespace {
int vertex_index(int divisions, int a, int b) {
  // Row a holds b = 0 .. d - a; rows before a hold sum_{r < a} (d + 1 - r) vertices.
  return a * (divisions + 1) - a * (a - 1) / 2 + b;
}
}  // namespace

int divisions_of(std::size_t n_vertices) {
  for (int d = 1; vertex_count(d) <= static_cast<int>(n_vertices); ++d)
    if (static_cast<std::size_t>(vertex_count(d)) == n_vertices) return d;
  return 0;
}

std::vector<std::array<double, 3>> direction_vertices(int divisions) {
  std::vector<std::array<double, 3>> out;
  for (int a = 0; a <= divisions; ++a)
    for (int b = 0; a + b <= divisions; ++b) {
      const double x = a, y = b, z = divisions - a - b, n = std::sqrt(x * x + y * y + z * z);
      out.push_back({x / n, y / n, z / n});
    }
  return out;
}

std::vector<std::array<int, 3>> direction_triangles(int divisions) {
  std::vector<std::array<int, 3>> out;
  for (int a = 0; a < divisions; ++a)
    for (int b = 0; a + b < divisions; ++b) {
      out.push_back({vertex_index(divisions, a, b), vertex_index(divisions, a + 1, b), vertex_index(divisions, a, b + 1)});
      if (a + b + 1 < divisions)
        out.push_back({vertex_index(divisions, a + 1, b), vertex_index(divisions, a, b + 1),
                       vertex_index(divisions, a + 1, b + 1)});
    }
  return out;
}

DirectionWeights locate_direction(const std::array<double, 3>& d, int divisions) {
  const int kDivisions = divisions;
  auto vertex_index = [&](int a, int b) { return ::clatter::kernels::pan::vertex_index(divisions, a, b); };
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
