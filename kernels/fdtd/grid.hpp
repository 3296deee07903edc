#pragma once
// Index spaces of the FDTD solver. Cells are cubes of side dx; pressure lives at cell centres.
// Full mode: n cells per axis (n even), centred on the origin, PML on all six faces.
// Octant mode: the positive octant only (cell centres at (i + 1/2) dx), mirror planes at the three
// low faces, PML on the three high faces: 1/8 of the work for the symmetric ellipsoid problems.
#include <array>
#include <cstddef>

namespace clatter::kernels::fdtd {

// Half-open box of global cell indices [lo, hi) per axis.
struct Box {
  std::array<int, 3> lo{}, hi{};
  bool empty() const { return hi[0] <= lo[0] || hi[1] <= lo[1] || hi[2] <= lo[2]; }
  long long cells() const {
    return empty() ? 0 : 1LL * (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  }
  Box intersect(const Box& o) const {
    Box b;
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = lo[a] > o.lo[a] ? lo[a] : o.lo[a];
      b.hi[a] = hi[a] < o.hi[a] ? hi[a] : o.hi[a];
    }
    return b;
  }
  bool contains(const std::array<int, 3>& c) const {
    for (int a = 0; a < 3; ++a)
      if (c[a] < lo[a] || c[a] >= hi[a]) return false;
    return true;
  }
};

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

// One rank's block of the grid, stored with a one-cell halo on every side, z fastest.
struct Layout {
  Box owned;  // global indices this rank updates
  std::array<long, 3> stride{};

  explicit Layout(const Box& b) : owned(b) {
    stride[2] = 1;
    stride[1] = owned.hi[2] - owned.lo[2] + 2;
    stride[0] = stride[1] * (owned.hi[1] - owned.lo[1] + 2);
  }
  std::size_t size() const { return static_cast<std::size_t>(stride[0] * (owned.hi[0] - owned.lo[0] + 2)); }
  std::array<int, 3> count() const {
    return {owned.hi[0] - owned.lo[0], owned.hi[1] - owned.lo[1], owned.hi[2] - owned.lo[2]};
  }
  // Storage index of global cell (i, j, k); valid for the owned box grown by one cell.
  long at(int i, int j, int k) const {
    return (i - owned.lo[0] + 1) * stride[0] + (j - owned.lo[1] + 1) * stride[1] + (k - owned.lo[2] + 1);
  }
  long at(const std::array<int, 3>& c) const { return at(c[0], c[1], c[2]); }
};

}  // namespace clatter::kernels::fdtd
