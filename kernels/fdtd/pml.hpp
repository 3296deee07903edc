#pragma once
// Perfectly matched layer (Berenger's split field, graded sigma = sigma_max (d/L)^3) in
// pressure-only form: only the split components of the damped axes are stored (velocity on faces
// plus two time levels of split pressure); the undamped components are eliminated exactly, as in
// the interior. A face slab costs 3 floats per cell, an edge 6, a corner 9 (docs/fdtd.md).
#include <array>
#include <cstddef>
#include <new>
#include <vector>

#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

// Storage for the big per-cell arrays (the Engine's fields, the layer's state): aligned to 2 MiB
// and, where the system has madvise, marked for transparent huge pages before the first touch,
// so the stencil's many concurrent row streams miss the TLB less. Falls back to plain aligned
// storage silently (docs/benchmarks.md).
void* allocate_huge(std::size_t bytes);
void free_huge(void* p, std::size_t bytes) noexcept;

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_huge(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { free_huge(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept { return false; }
};
using HugeVector = std::vector<float, HugePageAllocator<float>>;

// What the layer changes as it steps, per region of the Pml that made it.
struct PmlState {
  struct Region {
    std::array<HugeVector, 3> v;                     // face velocity, (count + e_a) faces per damped axis
    std::array<HugeVector, 3> split_now, split_old;  // p_a at t_n and t_(n-1)
  };
  std::vector<Region> regions;
};

// The layer's regions and coefficients: built once per geometry, never changed by stepping.
class Pml {
 public:
  Pml(const Problem& problem, const Layout& layout);

  PmlState make_state() const;  // at rest (all auxiliary fields 0)
  void reset(PmlState& state) const;
  // p_now: pressure at t_n with filled halo; p_next: holds p at t_(n-1) on entry, t_(n+1) on exit.
  void update(PmlState& state, const float* p_now, float* p_next) const { update(state, p_now, p_next, Box{}); }
  // The same, less the rows (i, j) within the x-y extent of `swept` of the z layers that
  // update_z_rows can take: a caller sweeping the rows of `swept` (the Engine's interior) has
  // already updated them through update_z_rows, while their neighbours were in cache. Call it after
  // those rows: it ends the step of every region.
  void update(PmlState& state, const float* p_now, float* p_next, const Box& swept) const;
  // Rows (i, j0..j1) of the z layers (regions damped along z alone, 3 % of a 256^3 grid's cells in
  // 6-cell pieces of rows) that need no halo: faces and cells of each row at once.
  void update_z_rows(PmlState& state, const float* p_now, float* p_next, int i, int j0, int j1) const;
  long long cells() const;
  std::size_t bytes() const;  // of one PmlState

 private:
  struct Region {
    Box box;                                           // owned cells of this region
    int damped = 0;                                    // bit a set: axis a is damped here
    std::array<std::array<long, 3>, 3> face_stride{};  // per damped axis, strides of its face array
    std::array<std::size_t, 3> faces{}, cells{};       // per damped axis, sizes of v and of each split part
    bool z_rows = false;  // damped along z alone, and its z faces read owned cells only (update_z_rows)
  };
  struct SplitRow {
    const float* vlo[3] = {};
    const float* vhi[3] = {};
    const float* now[3] = {};
    float* old[3] = {};
    float cdec[3] = {}, cgain[3] = {};
  };
  template <int D>
  void update_region(const Region& r, PmlState::Region& s, const float* p_now, float* p_next) const;
  template <int a>
  void update_faces(const Region& r, PmlState::Region& s, const float* p_now, int fi0, int fi1) const;
  void update_z_row(const Region& r, PmlState::Region& s, int ci, int cj, const float* p_now, float* p_next) const;
  template <int D>
  SplitRow split_row(const Region& r, PmlState::Region& s, int ci, int cj) const;
  template <int D>
  void update_pressure(const Region& r, PmlState::Region& s, const float* p_now, float* p_next, int ci) const;

  Layout layout_;
  Grid grid_;
  float lambda2_;
  std::vector<Region> regions_;
  std::vector<std::size_t> z_rows_;  // the regions update_z_rows takes
  // Per axis, over global cell index (cells) and face position (faces, between cells g-1 and g).
  std::array<std::vector<float>, 3> cell_decay_, cell_gain_, face_decay_, face_gain_;
};

}  // namespace clatter::kernels::fdtd
