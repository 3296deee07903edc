#include "kernels/pan/directions.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kernels/fdtd/geometry.hpp"

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

DirectionWeights locate_direction(const std::array<double, 3>& d, int divisions, Interpolation interpolation) {
  const bool quadratic = interpolation == Interpolation::quadratic;
  if (quadratic && divisions % 2 != 0)
    throw std::invalid_argument("locate_direction: quadratic interpolation needs an even number of divisions");
  const double s = d[0] + d[1] + d[2];
  if (!(s > 0) || d[0] < 0 || d[1] < 0 || d[2] < 0)
    throw std::invalid_argument("locate_direction: direction outside the positive octant");
  // The element lattice: the triangulation itself (linear) or its 2x coarser quadratic elements.
  const int cells = quadratic ? divisions / 2 : divisions, stride = quadratic ? 2 : 1;
  const double ua = cells * d[0] / s, ub = cells * d[1] / s;
  int a = std::min(static_cast<int>(std::floor(ua)), cells);
  int b = std::min(static_cast<int>(std::floor(ub)), cells - a);
  if (a + b == cells) {  // on the far edge: use the element just inside it
    if (a > 0)
      --a;
    else
      --b;
  }
  const double fa = ua - a, fb = ub - b;
  // Element corners (lattice coordinates of the fine triangulation) and barycentric coordinates.
  std::array<std::array<int, 2>, 3> corner;
  std::array<double, 3> l;
  // Rounding may put a point of the far edge just past it: keep it in the element below.
  if (fa + fb <= 1.0 || a + b + 1 == cells) {
    corner = {{{a, b}, {a + 1, b}, {a, b + 1}}};
    l = {1.0 - fa - fb, fa, fb};
  } else {
    corner = {{{a + 1, b + 1}, {a + 1, b}, {a, b + 1}}};
    l = {fa + fb - 1.0, 1.0 - fb, 1.0 - fa};
  }
  for (auto& c : corner) c = {stride * c[0], stride * c[1]};
  for (double& x : l) x = std::clamp(x, 0.0, 1.0);
  DirectionWeights w;
  w.count = quadratic ? 6 : 3;
  for (std::size_t i = 0; i < 3; ++i) {
    w.vertex[i] = vertex_index(divisions, corner[i][0], corner[i][1]);
    w.weight[i] = quadratic ? l[i] * (2 * l[i] - 1) : l[i];
  }
  if (quadratic)  // the six-node element: corners l(2l - 1), edge midpoints 4 l_i l_j
    for (std::size_t i = 0; i < 3; ++i) {
      const std::size_t j = (i + 1) % 3;
      w.vertex[3 + i] = vertex_index(divisions, (corner[i][0] + corner[j][0]) / 2, (corner[i][1] + corner[j][1]) / 2);
      w.weight[3 + i] = 4 * l[i] * l[j];
    }
  return w;
}

double symmetry_zeros(int field, const std::array<double, 3>& d) {
  double m = 1;
  for (int a = 0; a < 3; ++a)
    if (fdtd::field_parity(field, a) < 0) m *= std::abs(d[static_cast<std::size_t>(a)]);
  return m;
}

std::array<double, 3> off_planes(int field, const std::array<double, 3>& d) {
  std::array<double, 3> out = d;
  for (int a = 0; a < 3; ++a)
    if (fdtd::field_parity(field, a) < 0 && std::abs(out[static_cast<std::size_t>(a)]) < kOffPlane)
      out[static_cast<std::size_t>(a)] = kOffPlane;
  const double n = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  for (double& x : out) x /= n;
  return out;
}

}  // namespace clatter::kernels::pan
