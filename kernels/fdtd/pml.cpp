#include "kernels/fdtd/pml.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <type_traits>

#if defined(__has_include)
#if __has_include(<sys/mman.h>)
#include <sys/mman.h>
#endif
#endif

namespace clatter::kernels::fdtd {

void* allocate_huge(std::size_t bytes) {
  constexpr std::size_t huge = std::size_t{2} << 20, line = 64;
  const std::size_t align = bytes >= huge ? huge : line;
  const std::size_t size = (std::max<std::size_t>(bytes, 1) + align - 1) / align * align;
  void* p = std::aligned_alloc(align, size);
  if (p == nullptr) throw std::bad_alloc();
#if defined(MADV_HUGEPAGE)
  if (align == huge) (void)madvise(p, size, MADV_HUGEPAGE);  // advice only: ignored where unsupported
#endif
  return p;
}

void free_huge(void* p, std::size_t) noexcept { std::free(p); }

namespace {
// Depth (in cells) of a position, in cell units from the grid's low edge, into the absorbing layer.
double depth(const Grid& g, int axis, double position) {
  const double n = g.n[axis], l = g.pml;
  double d = position - (n - l);            // high layer
  if (!g.octant) d = std::max(d, l - position);  // low layer
  return std::max(d, 0.0);
}
}  // namespace

Pml::Pml(const Problem& problem, const Layout& layout)
    : layout_(layout), grid_(problem.grid), lambda2_(static_cast<float>(problem.courant() * problem.courant())) {
  const Grid& g = grid_;
  const double dt = problem.dt_s, dx = g.dx_m, rho = problem.rho_kg_m3, c = problem.c_m_s;
  const double l = g.pml;
  const double sigma_max = l > 0 ? -4.0 * c * std::log(problem.pml_reflection) / (2.0 * l * dx) : 0.0;
  auto sigma = [&](double d) { return l > 0 ? sigma_max * std::pow(d / l, 3) : 0.0; };
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i < g.n[a]; ++i) {
      const double s = sigma(depth(g, a, i + 0.5)), den = 1.0 + 0.5 * s * dt;
      cell_decay_[a].push_back(static_cast<float>((1.0 - 0.5 * s * dt) / den));
      cell_gain_[a].push_back(static_cast<float>(rho * c * c * dt / dx / den));
    }
    for (int f = 0; f <= g.n[a]; ++f) {
      const double s = sigma(depth(g, a, f)), den = 1.0 + 0.5 * s * dt;
      face_decay_[a].push_back(static_cast<float>((1.0 - 0.5 * s * dt) / den));
      face_gain_[a].push_back(static_cast<float>(dt / (rho * dx) / den));
    }
  }
  if (g.pml == 0) return;
  // Split each axis into layer and middle segments; every combination but all-middle is a region.
  std::array<std::vector<std::pair<Box, bool>>, 3> segments;
  for (int a = 0; a < 3; ++a) {
    auto seg = [&](int lo, int hi, bool damped) {
      Box b = g.all();
      b.lo[a] = lo;
      b.hi[a] = hi;
      segments[a].push_back({b, damped});
    };
    if (!g.octant) seg(0, g.pml, true);
    seg(g.octant ? 0 : g.pml, g.n[a] - g.pml, false);
    seg(g.n[a] - g.pml, g.n[a], true);
  }
  for (const auto& [bx, dx_damped] : segments[0])
    for (const auto& [by, dy_damped] : segments[1])
      for (const auto& [bz, dz_damped] : segments[2]) {
        const int damped = (dx_damped ? 1 : 0) | (dy_damped ? 2 : 0) | (dz_damped ? 4 : 0);
        if (damped == 0) continue;
        Region r;
        r.box = bx.intersect(by).intersect(bz).intersect(layout.owned);
        if (r.box.empty()) continue;
        r.damped = damped;
        r.z_rows = damped == 4 && (r.box.lo[2] == 0 || r.box.lo[2] - 1 >= layout.owned.lo[2]) &&
                   (r.box.hi[2] == g.n[2] || r.box.hi[2] < layout.owned.hi[2]);
        if (r.z_rows) z_rows_.push_back(regions_.size());
        const auto n = std::array<int, 3>{r.box.hi[0] - r.box.lo[0], r.box.hi[1] - r.box.lo[1], r.box.hi[2] - r.box.lo[2]};
        for (int a = 0; a < 3; ++a) {
          if (!(damped & (1 << a))) continue;
          auto fn = n;
          fn[a] += 1;
          r.face_stride[a] = {long(fn[1]) * fn[2], fn[2], 1};
          r.faces[a] = static_cast<std::size_t>(fn[0]) * fn[1] * fn[2];
          r.cells[a] = static_cast<std::size_t>(n[0]) * n[1] * n[2];
        }
        regions_.push_back(std::move(r));
      }
}

PmlState Pml::make_state() const {
  PmlState state;
  for (const auto& r : regions_) {
    PmlState::Region& s = state.regions.emplace_back();
    for (int a = 0; a < 3; ++a) {
      s.v[a].assign(r.faces[a], 0.0f);
      s.split_now[a].assign(r.cells[a], 0.0f);
      s.split_old[a].assign(r.cells[a], 0.0f);
    }
  }
  return state;
}

void Pml::reset(PmlState& state) const {
  for (auto& s : state.regions)
    for (int a = 0; a < 3; ++a) {
      std::fill(s.v[a].begin(), s.v[a].end(), 0.0f);
      std::fill(s.split_now[a].begin(), s.split_now[a].end(), 0.0f);
      std::fill(s.split_old[a].begin(), s.split_old[a].end(), 0.0f);
    }
}

long long Pml::cells() const {
  long long n = 0;
  for (const auto& r : regions_) n += r.box.cells();
  return n;
}

std::size_t Pml::bytes() const {
  std::size_t b = 0;
  for (const auto& r : regions_)
    for (int a = 0; a < 3; ++a) b += (r.faces[a] + 2 * r.cells[a]) * sizeof(float);
  return b;
}

void Pml::update(PmlState& state, const float* p_now, float* p_next, const Box& swept) const {
  for (std::size_t i = 0; i < regions_.size(); ++i) {
    const Region& r = regions_[i];
    PmlState::Region& s = state.regions[i];
    switch (r.damped) {
      case 1: update_region<1>(r, s, p_now, p_next); break;
      case 2: update_region<2>(r, s, p_now, p_next); break;
      case 3: update_region<3>(r, s, p_now, p_next); break;
      case 4: {
        const Box& b = r.box;
        for (int ci = 0; ci < b.hi[0] - b.lo[0]; ++ci) {
          const int gi = b.lo[0] + ci;
          const bool in_x = r.z_rows && gi >= swept.lo[0] && gi < swept.hi[0];
          for (int cj = 0; cj < b.hi[1] - b.lo[1]; ++cj) {
            const int gj = b.lo[1] + cj;
            if (in_x && gj >= swept.lo[1] && gj < swept.hi[1]) continue;  // done by update_z_rows
            update_z_row(r, s, ci, cj, p_now, p_next);
          }
        }
        break;
      }
      case 5: update_region<5>(r, s, p_now, p_next); break;
      case 6: update_region<6>(r, s, p_now, p_next); break;
      default: update_region<7>(r, s, p_now, p_next); break;
    }
    for (int a = 0; a < 3; ++a) s.split_now[a].swap(s.split_old[a]);
  }
}

void Pml::update_z_rows(PmlState& state, const float* p_now, float* p_next, int i, int j0, int j1) const {
  for (const std::size_t x : z_rows_) {
    const Region& r = regions_[x];
    if (i < r.box.lo[0] || i >= r.box.hi[0]) continue;
    const int lo = std::max(j0, r.box.lo[1]), hi = std::min(j1, r.box.hi[1]);
    for (int j = lo; j < hi; ++j) update_z_row(r, state.regions[x], i - r.box.lo[0], j - r.box.lo[1], p_now, p_next);
  }
}

namespace {

// One row of a region damped along z alone: its z faces (k0..k1) from the gradient of p^n, then
// its nk cells, with the arithmetic of update_faces<2> and update_pressure<4>. Inlined with nk = 6
// (the usual layer) as a constant, so the row is a few masked vectors.
[[gnu::always_inline]] inline void z_row(const float* __restrict p, float* __restrict q, float* __restrict v,
                                         const float* __restrict nz, float* __restrict oz, const float* __restrict fd,
                                         const float* __restrict fg, const float* __restrict zdec,
                                         const float* __restrict zgain, long sx, long sy, float l2, int k0, int k1,
                                         int nk) {
#pragma omp simd
  for (int k = k0; k < k1; ++k) v[k] = fd[k] * v[k] - fg[k] * (p[k] - p[k - 1]);
  const float* __restrict pxm = p - sx;
  const float* __restrict pxp = p + sx;
  const float* __restrict pym = p - sy;
  const float* __restrict pyp = p + sy;
  const float centre = 4.0f;  // 2 x the two undamped axes
#pragma omp simd
  for (int k = 0; k < nk; ++k) {
    float split = 0.0f, pairs = 0.0f;
    pairs += pxm[k] + pxp[k];
    pairs += pym[k] + pyp[k];
    const float next = zdec[k] * nz[k] - zgain[k] * (v[k + 1] - v[k]);
    split += (next - 2.0f * nz[k]) + oz[k];
    oz[k] = next;
    q[k] = (2.0f * p[k] - q[k]) + l2 * (pairs - centre * p[k]) + split;
  }
}

}  // namespace

void Pml::update_z_row(const Region& r, PmlState::Region& s, int ci, int cj, const float* p_now, float* p_next) const {
  const Box& b = r.box;
  const int n1 = b.hi[1] - b.lo[1], nk = b.hi[2] - b.lo[2];
  const long cell = layout_.at(b.lo[0] + ci, b.lo[1] + cj, b.lo[2]);
  const long local = (long(ci) * n1 + cj) * nk;
  float* v = s.v[2].data() + ci * r.face_stride[2][0] + cj * r.face_stride[2][1];
  const float* nz = s.split_now[2].data() + local;
  float* oz = s.split_old[2].data() + local;
  const float* fd = face_decay_[2].data() + b.lo[2];
  const float* fg = face_gain_[2].data() + b.lo[2];
  const float* zdec = cell_decay_[2].data() + b.lo[2];
  const float* zgain = cell_gain_[2].data() + b.lo[2];
  const int k0 = b.lo[2] == 0 ? 1 : 0, k1 = b.hi[2] == grid_.n[2] ? nk : nk + 1;
  const long sx = layout_.stride[0], sy = layout_.stride[1];
  if (nk == 6 && k0 == 0 && k1 == 7)
    z_row(p_now + cell, p_next + cell, v, nz, oz, fd, fg, zdec, zgain, sx, sy, lambda2_, 0, 7, 6);
  else if (nk == 6 && k0 == 1 && k1 == 7)
    z_row(p_now + cell, p_next + cell, v, nz, oz, fd, fg, zdec, zgain, sx, sy, lambda2_, 1, 7, 6);
  else if (nk == 6 && k0 == 0 && k1 == 6)
    z_row(p_now + cell, p_next + cell, v, nz, oz, fd, fg, zdec, zgain, sx, sy, lambda2_, 0, 6, 6);
  else
    z_row(p_now + cell, p_next + cell, v, nz, oz, fd, fg, zdec, zgain, sx, sy, lambda2_, k0, k1, nk);
}

// Face velocities of damped axis `a` from the pressure gradient at t_n. Faces on the grid's outer
// boundary stay 0 (a rigid wall behind the layer) and are never updated.
template <int a>
void Pml::update_faces(const Region& r, PmlState::Region& s, const float* p_now, int fi0, int fi1) const {
  const Box& b = r.box;
  const auto& st = layout_.stride;
  const std::array<int, 3> n{b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]};
  const auto& fs = r.face_stride[a];
  const float* fd = face_decay_[a].data();
  const float* fg = face_gain_[a].data();
  float* v = s.v[a].data();
  for (int fi = fi0; fi < fi1; ++fi) {
    const int gi = b.lo[0] + fi;
    if (a == 0 && (gi == 0 || gi == grid_.n[0])) continue;
    for (int fj = 0; fj < n[1] + (a == 1); ++fj) {
      const int gj = b.lo[1] + fj;
      if (a == 1 && (gj == 0 || gj == grid_.n[1])) continue;
      const long cell = layout_.at(gi, gj, b.lo[2]);
      float* __restrict vrow = v + fi * fs[0] + fj * fs[1];
      const float* __restrict p = p_now + cell;
      const float* __restrict pm = p_now + cell - st[a];
      if (n[2] < 64) __builtin_prefetch(p + 2 * st[1]);
      if constexpr (a == 2) {
        const int k0 = b.lo[2] == 0 ? 1 : 0, k1 = b.hi[2] == grid_.n[2] ? n[2] : n[2] + 1;
#pragma omp simd
        for (int k = k0; k < k1; ++k) vrow[k] = fd[b.lo[2] + k] * vrow[k] - fg[b.lo[2] + k] * (p[k] - pm[k]);
      } else {
        const int g = a == 0 ? gi : gj;
        const float d = fd[g], e = fg[g];
#pragma omp simd
        for (int k = 0; k < n[2]; ++k) vrow[k] = d * vrow[k] - e * (p[k] - pm[k]);
      }
    }
  }
}

// Per damped axis of row (ci, cj): split parts (now, old -> next), face velocities below and above
// the cell, and the x and y cell coefficients.
template <int D>
Pml::SplitRow Pml::split_row(const Region& r, PmlState::Region& s, int ci, int cj) const {
  const Box& b = r.box;
  const std::array<int, 3> n{b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]};
  const long local = (long(ci) * n[1] + cj) * n[2];
  SplitRow row;
  for (int a = 0; a < 3; ++a) {
    if (!(D & (1 << a))) continue;
    const auto& fs = r.face_stride[a];
    row.vlo[a] = s.v[a].data() + ci * fs[0] + cj * fs[1];
    row.vhi[a] = row.vlo[a] + fs[a];
    row.now[a] = s.split_now[a].data() + local;
    row.old[a] = s.split_old[a].data() + local;
    if (a < 2) {
      const int g = a == 0 ? b.lo[0] + ci : b.lo[1] + cj;
      row.cdec[a] = cell_decay_[a][static_cast<std::size_t>(g)];
      row.cgain[a] = cell_gain_[a][static_cast<std::size_t>(g)];
    }
  }
  return row;
}

// Pressure of one region: damped split parts explicitly, undamped parts through the leapfrog Laplacian.
template <int D>
void Pml::update_pressure(const Region& r, PmlState::Region& s, const float* p_now, float* p_next, int ci) const {
  const Box& b = r.box;
  const auto& st = layout_.stride;
  const std::array<int, 3> n{b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]};
  constexpr int undamped = 3 - ((D & 1) != 0) - ((D & 2) != 0) - ((D & 4) != 0);
  const float l2 = lambda2_, centre = 2.0f * static_cast<float>(undamped);
  const long sx = st[0], sy = st[1];
  for (int cj = 0; cj < n[1]; ++cj) {
      const long cell = layout_.at(b.lo[0] + ci, b.lo[1] + cj, b.lo[2]);
      const float* __restrict p = p_now + cell;
      float* __restrict q = p_next + cell;
      const SplitRow row = split_row<D>(r, s, ci, cj);
      // Named restrict pointers (not arrays of pointers) so the compiler vectorizes the k loop.
      const float* __restrict zdec = cell_decay_[2].data() + b.lo[2];
      const float* __restrict zgain = cell_gain_[2].data() + b.lo[2];
      const float* __restrict nx = row.now[0];
      const float* __restrict ny = row.now[1];
      const float* __restrict nz = row.now[2];
      float* __restrict ox = row.old[0];
      float* __restrict oy = row.old[1];
      float* __restrict oz = row.old[2];
      const float* __restrict lx = row.vlo[0];
      const float* __restrict hx = row.vhi[0];
      const float* __restrict ly = row.vlo[1];
      const float* __restrict hy = row.vhi[1];
      const float* __restrict lz = row.vlo[2];
      const float* __restrict hz = row.vhi[2];
      const float* __restrict pxm = p - sx;
      const float* __restrict pxp = p + sx;
      const float* __restrict pym = p - sy;
      const float* __restrict pyp = p + sy;
      const float dx0 = row.cdec[0], gx0 = row.cgain[0], dy0 = row.cdec[1], gy0 = row.cgain[1];
      // No runtime alias checks (the arrays never overlap): they would dominate the 6-cell z rows.
      if (n[2] < 64) {
        // Short rows (the z layers) touch a few cache lines 1 KB apart: fetch the rows two ahead,
        // or every row waits on DRAM latency (measured: 7x slower without).
        __builtin_prefetch(p + 2 * sy);
        __builtin_prefetch(pxm + 2 * sy);
        __builtin_prefetch(pxp + 2 * sy);
        __builtin_prefetch(q + 2 * sy, 1);
      }
#pragma omp simd
      for (int k = 0; k < n[2]; ++k) {
        float split = 0.0f, pairs = 0.0f;
        if constexpr ((D & 1) != 0) {
          const float next = dx0 * nx[k] - gx0 * (hx[k] - lx[k]);
          split += (next - 2.0f * nx[k]) + ox[k];
          ox[k] = next;
        } else {
          pairs += pxm[k] + pxp[k];
        }
        if constexpr ((D & 2) != 0) {
          const float next = dy0 * ny[k] - gy0 * (hy[k] - ly[k]);
          split += (next - 2.0f * ny[k]) + oy[k];
          oy[k] = next;
        } else {
          pairs += pym[k] + pyp[k];
        }
        if constexpr ((D & 4) != 0) {
          const float next = zdec[k] * nz[k] - zgain[k] * (hz[k] - lz[k]);
          split += (next - 2.0f * nz[k]) + oz[k];
          oz[k] = next;
        } else {
          pairs += p[k - 1] + p[k + 1];
        }
        q[k] = (2.0f * p[k] - q[k]) + l2 * (pairs - centre * p[k]) + split;
      }
    }
}

// Plane by plane (x): the faces a plane's cells read, then its cells, while that plane's p^n is
// still in cache. Faces depend on p^n alone, so the order does not change a bit.
template <int D>
void Pml::update_region(const Region& r, PmlState::Region& s, const float* p_now, float* p_next) const {
  const int n0 = r.box.hi[0] - r.box.lo[0];
  if constexpr ((D & 1) != 0) update_faces<0>(r, s, p_now, 0, 1);
  for (int ci = 0; ci < n0; ++ci) {
    if constexpr ((D & 1) != 0) update_faces<0>(r, s, p_now, ci + 1, ci + 2);
    if constexpr ((D & 2) != 0) update_faces<1>(r, s, p_now, ci, ci + 1);
    if constexpr ((D & 4) != 0) update_faces<2>(r, s, p_now, ci, ci + 1);
    update_pressure<D>(r, s, p_now, p_next, ci);
  }
}

}  // namespace clatter::kernels::fdtd
