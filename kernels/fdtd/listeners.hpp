#pragma once
// Listeners: tricubic Lagrange interpolation (4 cell centres per axis, 64 in all; error
// O((k dx)^4), as small as the me4 scheme's own) of the cell-centred pressure at arbitrary points.
// Trilinear interpolation would cost up to 1.4 % per axis at the paper's resolution
// (docs/fdtd.md, error budget). The weights come from |x| and the cells are mirrored for negative
// coordinates, so a point's value is computed the same way in full and octant mode (bit-identical).
#include <array>
#include <optional>
#include <string>

#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

struct Stencil {
  static constexpr int kPoints = 4;                        // per axis
  static constexpr int kCorners = kPoints * kPoints * kPoints;
  std::array<std::array<int, 3>, kCorners> cell{};  // cells of the solved grid; c = 16 bx + 4 by + bz
  std::array<int, kCorners> sign{};                 // octant mode: parity of the field for mirrored cells
  std::array<std::array<double, kPoints>, 3> weight{};  // Lagrange weight of point b along each axis
};

Stencil listener_stencil(const Problem& problem, const std::array<double, 3>& x_m);

// Why this point cannot be a listener (outside the grid, in the PML, inside or too close to the
// body), or nullopt when it can.
std::optional<std::string> listener_problem(const Problem& problem, const std::array<double, 3>& x_m);

// Interpolates from the corner values (sign not yet applied), always in the same order.
double interpolate(const Stencil& s, const std::array<float, Stencil::kCorners>& corner_values);

}  // namespace clatter::kernels::fdtd
