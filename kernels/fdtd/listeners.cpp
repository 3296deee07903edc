#include "kernels/fdtd/listeners.hpp"

#include <cmath>
#include <string>

namespace clatter::kernels::fdtd {

Stencil listener_stencil(const Problem& problem, const std::array<double, 3>& x_m) {
  const Grid& g = problem.grid;
  constexpr int np = Stencil::kPoints;
  Stencil s;
  std::array<std::array<int, np>, 3> cells{};  // per axis: cell index of point b = 0..3
  std::array<std::array<int, np>, 3> signs{};
  for (int a = 0; a < 3; ++a) {
    const double u = std::abs(x_m[a]) / g.dx_m - 0.5;  // position in cell-centre units, from the origin
    const double base = std::floor(u), t = u - base;   // points at base - 1 .. base + 2, t in [0, 1)
    // Cubic Lagrange weights of the nodes -1, 0, 1, 2 at t.
    s.weight[a] = {-t * (t - 1) * (t - 2) / 6, (t + 1) * (t - 1) * (t - 2) / 2, -(t + 1) * t * (t - 2) / 2,
                   (t + 1) * t * (t - 1) / 6};
    for (int b = 0; b < np; ++b) {
      int rel = static_cast<int>(base) - 1 + b;  // cell whose centre is at (rel + 1/2) dx
      if (x_m[a] < 0) rel = -1 - rel;            // the mirror image, for points on the negative side
      int sign = 1;
      if (g.octant && rel < 0) {
        rel = -1 - rel;
        sign = problem.parity(a);
      }
      cells[a][static_cast<std::size_t>(b)] = rel + g.origin(a);
      signs[a][static_cast<std::size_t>(b)] = sign;
    }
  }
  for (int c = 0; c < Stencil::kCorners; ++c) {
    const std::size_t bx = static_cast<std::size_t>(c / (np * np)), by = static_cast<std::size_t>((c / np) % np),
                      bz = static_cast<std::size_t>(c % np);
    s.cell[static_cast<std::size_t>(c)] = {cells[0][bx], cells[1][by], cells[2][bz]};
    s.sign[static_cast<std::size_t>(c)] = signs[0][bx] * signs[1][by] * signs[2][bz];
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
  // me4 blends into the 7-point layer over the last cells before it.
  const int blend = blend_cells(problem.scheme, g.pml);
  Box unblended = full_interior;
  for (int a = 0; a < 3; ++a) {
    unblended.lo[a] += blend;
    unblended.hi[a] -= blend;
  }
  for (const auto& c : fs.cell) {
    if (!full_all.contains(c)) return std::string("outside the domain");
    if (!full_interior.contains(c)) return std::string("inside the absorbing layer (PML)");
    if (!unblended.contains(c))
      return std::string("within ") + std::to_string(blend) +
             " cells of the absorbing layer, where the scheme blends into it (grow grid.half_width_m)";
  }
  if (problem.field != 0) {
    const SolidBody& e = problem.solid();
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

double interpolate(const Stencil& s, const std::array<float, Stencil::kCorners>& v) {
  constexpr int np = Stencil::kPoints;
  // z, then y, then x, each a fixed-order sum of four terms.
  double x_sum = 0;
  for (int bx = 0; bx < np; ++bx) {
    double y_sum = 0;
    for (int by = 0; by < np; ++by) {
      double z_sum = 0;
      for (int bz = 0; bz < np; ++bz) {
        const std::size_t c = static_cast<std::size_t>((bx * np + by) * np + bz);
        z_sum += s.weight[2][static_cast<std::size_t>(bz)] * (static_cast<double>(s.sign[c]) * static_cast<double>(v[c]));
      }
      y_sum += s.weight[1][static_cast<std::size_t>(by)] * z_sum;
    }
    x_sum += s.weight[0][static_cast<std::size_t>(bx)] * y_sum;
  }
  // + 0.0 turns -0 into +0: a mirrored zero (-1 * 0) and a computed zero then have the same bits.
  return x_sum + 0.0;
}

}  // namespace clatter::kernels::fdtd
