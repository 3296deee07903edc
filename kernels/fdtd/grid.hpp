#pragma once
// Index spaces of the FDTD solver. Cells are cubes of side dx; pressure lives at cell centres.
// Full mode: n cells per axis (n even), centred on the origin, PML on all six faces.
// Octant mode: the positive octant only (cell centres at (i + 1/2) dx), mirror planes at the three
// low faces, PML on the three high faces: 1/8 of the work for the symmetric ellipsoid problems.
#include <array>

#include "core/block_layout.hpp"

namespace clatter::kernels::fdtd {

// The block storage contract shared with the halo exchanges (core/block_layout.hpp).
using Box = clatter::Box;
using Layout = clatter::BlockLayout;

struct Grid {
  std::array<int, 3> n{};  // cells per axis of the solved domain
  double dx_m = 0;
  bool octant = false;
  int pml = 0;  // PML thickness in cells

  // Index of the cell at the origin's positive side: cell i has centre (i - origin + 1/2) dx.
  int origin(int axis) const { return octant ? 0 : n[axis] / 2; }
  double centre_m(int axis, int i) const { return (i - origin(axis) + 0.5) * dx_m; }
  Box all() const { return {{0, 0, 0}, n}; }
  // Cells outside the absorbing layer.
  Box interior() const {
    Box b = all();
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = octant ? 0 : pml;
      b.hi[a] = n[a] - pml;
    }
    return b;
  }
};

}  // namespace clatter::kernels::fdtd
