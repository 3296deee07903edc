#pragma once
// The storage of one block of a 3D cell grid, the one contract between the kernels that update it
// and the halo exchanges (mpi/, tests) that fill its halo: the block's cells in a box of global
// indices, stored with a two-cell halo on every side, z fastest. Standard library only.
#include <array>
#include <cstddef>
#include <utility>

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

// A box of storage positions (0 = the outer low halo layer) within a block's (n + 4)^3-shaped storage.
struct StorageRegion {
  std::array<int, 3> start{}, count{};
};

// One block stored with a halo of kHalo cells on every side, z fastest. Two cells, because the
// fourth-order scheme reads neighbours two cells away along the axes (docs/fdtd.md).
struct BlockLayout {
  static constexpr int kHalo = 2;
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
  // Storage shape per axis: the owned cells and the halo layers on both sides.
  std::array<int, 3> extent() const {
    const auto n = count();
    return {n[0] + 2 * kHalo, n[1] + 2 * kHalo, n[2] + 2 * kHalo};
  }
  std::size_t size() const { return static_cast<std::size_t>(stride[0] * extent()[0]); }
  // Storage index of global cell (i, j, k); valid for the owned box grown by kHalo cells.
  long at(int i, int j, int k) const {
    return (i - owned.lo[0] + kHalo) * stride[0] + (j - owned.lo[1] + kHalo) * stride[1] + (k - owned.lo[2] + kHalo);
  }
  long at(const std::array<int, 3>& c) const { return at(c[0], c[1], c[2]); }

  // The kHalo layers of owned cells on `side` (0 low, 1 high) of `axis` that a neighbour there
  // reads (halo = false), or the halo layers it fills (halo = true). Needs count() >= kHalo.
  StorageRegion face(int axis, int side, bool halo) const {
    const auto n = count();
    StorageRegion r{{kHalo, kHalo, kHalo}, n};
    r.count[axis] = kHalo;
    if (halo)
      r.start[axis] = side == 0 ? 0 : n[axis] + kHalo;
    else
      r.start[axis] = side == 0 ? kHalo : n[axis];
    return r;
  }
  // The one-cell-thick edge along the third axis where the faces (axis_a, side_a) and
  // (axis_b, side_b) meet: the cells the diagonal neighbour there reads (halo = false) or the halo
  // cells it fills. Face-diagonal stencil points (+-1, +-1) need these; corners are never read.
  StorageRegion edge(int axis_a, int side_a, int axis_b, int side_b, bool halo) const {
    const auto n = count();
    StorageRegion r{{kHalo, kHalo, kHalo}, n};
    for (auto [axis, side] : {std::pair{axis_a, side_a}, std::pair{axis_b, side_b}}) {
      r.count[axis] = 1;
      if (halo)
        r.start[axis] = side == 0 ? kHalo - 1 : n[axis] + kHalo;
      else
        r.start[axis] = side == 0 ? kHalo : n[axis] + kHalo - 1;
    }
    return r;
  }
};

}  // namespace clatter
