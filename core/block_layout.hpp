#pragma once
// The storage of one block of a 3D cell grid, the one contract between the kernels that update it
// and the halo exchanges (mpi/, tests) that fill its halo: the block's cells in a box of global
// indices, stored with a one-cell halo on every side, z fastest. Standard library only.
#include <array>
#include <cstddef>

namespace clatter {

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

// A box of storage positions (0 = the low halo layer) within a block's (n + 2)^3-shaped storage.
struct StorageRegion {
  std::array<int, 3> start{}, count{};
};

// One block stored with a one-cell halo on every side, z fastest.
struct BlockLayout {
  Box owned;  // global indices this block updates
  std::array<long, 3> stride{};

  explicit BlockLayout(const Box& b) : owned(b) {
    const auto e = extent();
    stride[2] = 1;
    stride[1] = e[2];
    stride[0] = stride[1] * e[1];
  }
  std::array<int, 3> count() const {
    return {owned.hi[0] - owned.lo[0], owned.hi[1] - owned.lo[1], owned.hi[2] - owned.lo[2]};
  }
  // Storage shape per axis: the owned cells and the two halo layers.
  std::array<int, 3> extent() const {
    const auto n = count();
    return {n[0] + 2, n[1] + 2, n[2] + 2};
  }
  std::size_t size() const { return static_cast<std::size_t>(stride[0] * extent()[0]); }
  // Storage index of global cell (i, j, k); valid for the owned box grown by one cell.
  long at(int i, int j, int k) const {
    return (i - owned.lo[0] + 1) * stride[0] + (j - owned.lo[1] + 1) * stride[1] + (k - owned.lo[2] + 1);
  }
  long at(const std::array<int, 3>& c) const { return at(c[0], c[1], c[2]); }

  // The face of the owned cells on `side` (0 low, 1 high) of `axis`: the layer a neighbour there
  // reads (halo = false) or the halo layer it fills (halo = true). Edges and corners are left out:
  // a 7-point stencil never reads them.
  StorageRegion face(int axis, int side, bool halo) const {
    const auto n = count();
    StorageRegion r{{1, 1, 1}, n};
    r.count[axis] = 1;
    if (halo)
      r.start[axis] = side == 0 ? 0 : n[axis] + 1;
    else
      r.start[axis] = side == 0 ? 1 : n[axis];
    return r;
  }
};

}  // namespace clatter
