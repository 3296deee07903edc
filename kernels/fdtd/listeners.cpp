#include "kernels/fdtd/listeners.hpp"

#include <cmath>

namespace clatter::kernels::fdtd {

Stencil listener_stencil(const Problem& problem, const std::array<double, 3>& x_m) {
  const Grid& g = problem.grid;
  Stencil s;
  std::array<std::array<int, 2>, 3> cells{};  // per axis: cell index of corner b = 0, 1
  std::array<std::array<int, 2>, 3> signs{};
  for (int a = 0; a < 3; ++a) {
    const double u = std::abs(x_m[a]) / g.dx_m - 0.5;  // position in cell-centre units, from the origin
    const double base = std::floor(u);
    s.weight[a] = u - base;
    for (int b = 0; b < 2; ++b) {
      int rel = static_cast<int>(base) + b;  // cell whose centre is at (rel + 1/2) dx
      if (x_m[a] < 0) rel = -1 - rel;        // the mirror image, for points on the negative side
      int sign = 1;
      if (g.octant && rel < 0) {
        rel = -1 - rel;
        sign = problem.parity(a);
      }
      cells[a][b] = rel + g.origin(a);
      signs[a][b] = sign;
    }
  }
  for (int c = 0; c < 8; ++c) {
    const int bx = (c >> 2) & 1, by = (c >> 1) & 1, bz = c & 1;
    s.cell[c] = {cells[0][bx], cells[1][by], cells[2][bz]};
    s.sign[c] = signs[0][bx] * signs[1][by] * signs[2][bz];
  }
  return s;
}

std::optional<std::string> listener_problem(const Problem& problem, const std::array<double, 3>& x_m) {
  const Grid& g = problem.grid;
  // Check the stencil as the full grid would see it, so octant and full mode accept the same points.
  Problem full = problem;
  full.grid.octant = false;
  full.grid.n = {2 * (g.octant ? g.n[0] : g.n[0] / 2), 2 * (g.octant ? g.n[1] : g.n[1] / 2),
                 2 * (g.octant ? g.n[2] : g.n[2] / 2)};
  const Stencil fs = listener_stencil(full, x_m);
  const Box full_all = full.grid.all();
  const Box full_interior = full.grid.interior();
  for (const auto& c : fs.cell) {
    if (!full_all.contains(c)) return std::string("outside the domain");
    if (!full_interior.contains(c)) return std::string("inside the absorbing layer (PML)");
  }
  if (problem.field != 0) {
    const Ellipsoid& e = problem.body;
    if (e.contains(x_m[0], x_m[1], x_m[2])) return std::string("inside the object");
    for (const auto& c : fs.cell) {
      const CellGeometry geo = cell_geometry(
          e, {full.grid.centre_m(0, c[0]), full.grid.centre_m(1, c[1]), full.grid.centre_m(2, c[2])}, g.dx_m,
          problem.cut_cell_samples);
      if (geo.solid()) return std::string("too close to the object (its interpolation cells reach inside it)");
    }
  }
  return std::nullopt;
}

double interpolate(const Stencil& s, const std::array<float, 8>& v) {
  auto corner = [&](int c) { return static_cast<double>(s.sign[c]) * static_cast<double>(v[c]); };
  auto lerp = [](double a, double b, double w) { return (1.0 - w) * a + w * b; };
  const double wx = s.weight[0], wy = s.weight[1], wz = s.weight[2];
  const double x0 = lerp(lerp(corner(0), corner(1), wz), lerp(corner(2), corner(3), wz), wy);
  const double x1 = lerp(lerp(corner(4), corner(5), wz), lerp(corner(6), corner(7), wz), wy);
  // + 0.0 turns -0 into +0: a mirrored zero (-1 * 0) and a computed zero then have the same bits.
  return lerp(x0, x1, wx) + 0.0;
}

}  // namespace clatter::kernels::fdtd
