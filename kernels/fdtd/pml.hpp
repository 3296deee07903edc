#pragma once
// Perfectly matched layer (Berenger's split field, graded sigma = sigma_max (d/L)^3) in
// pressure-only form: only the split components of the damped axes are stored (velocity on faces
// plus two time levels of split pressure); the undamped components are eliminated exactly, as in
// the interior. A face slab costs 3 floats per cell, an edge 6, a corner 9 (docs/fdtd.md).
#include <array>
#include <cstddef>
#include <vector>

#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

// What the layer changes as it steps, per region of the Pml that made it.
struct PmlState {
  struct Region {
    std::array<std::vector<float>, 3> v;                     // face velocity, (count + e_a) faces per damped axis
    std::array<std::vector<float>, 3> split_now, split_old;  // p_a at t_n and t_(n-1)
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
  void update(PmlState& state, const float* p_now, float* p_next) const;
  long long cells() const;
  std::size_t bytes() const;  // of one PmlState

 private:
  struct Region {
    Box box;                                           // owned cells of this region
    int damped = 0;                                    // bit a set: axis a is damped here
    std::array<std::array<long, 3>, 3> face_stride{};  // per damped axis, strides of its face array
    std::array<std::size_t, 3> faces{}, cells{};       // per damped axis, sizes of v and of each split part
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
  void update_faces(const Region& r, PmlState::Region& s, const float* p_now) const;
  template <int D>
  SplitRow split_row(const Region& r, PmlState::Region& s, int ci, int cj) const;
  template <int D>
  void update_pressure(const Region& r, PmlState::Region& s, const float* p_now, float* p_next) const;

  Layout layout_;
  Grid grid_;
  float lambda2_;
  std::vector<Region> regions_;
  // Per axis, over global cell index (cells) and face position (faces, between cells g-1 and g).
  std::array<std::vector<float>, 3> cell_decay_, cell_gain_, face_decay_, face_gain_;
};

}  // namespace clatter::kernels::fdtd
