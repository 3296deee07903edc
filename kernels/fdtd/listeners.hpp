#pragma once
// Listeners: trilinear (second-order) interpolation of the cell-centred pressure at arbitrary
// points. The weights come from |x| and the cells are mirrored for negative coordinates, so a
// point's value is computed the same way in full and octant mode (bit-identical results).
#include <array>
#include <optional>
#include <string>

#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

struct Stencil {
  std::array<std::array<int, 3>, 8> cell{};  // cells of the solved grid; corner c = 4 bx + 2 by + bz
  std::array<int, 8> sign{};                 // octant mode: parity of the field for mirrored cells
  std::array<double, 3> weight{};            // weight of the far (b = 1) corner along each axis
};

Stencil listener_stencil(const Problem& problem, const std::array<double, 3>& x_m);

// Why this point cannot be a listener (outside the grid, in the PML, inside or too close to the
// body), or nullopt when it can.
std::optional<std::string> listener_problem(const Problem& problem, const std::array<double, 3>& x_m);

// Interpolates from the eight corner values (sign not yet applied), always in the same order.
double interpolate(const Stencil& s, const std::array<float, 8>& corner_values);

}  // namespace clatter::kernels::fdtd
