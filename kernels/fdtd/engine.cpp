#include "kernels/fdtd/engine.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <type_traits>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "core/stage_log.hpp"
#include "kernels/pulse.hpp"

namespace clatter::kernels::fdtd {

namespace {

// The three neighbour sums of the me4 stencil at cell k of the row p (strides sx, sy): the 6 axis
// neighbours, the 6 at distance 2, and the 12 face diagonals. Every group pairs points that a
// mirror across x, y or z swaps, and groups are added in a fixed order, so mirrored cells round
// identically (octant mode is bit-exact, docs/fdtd.md). The face diagonals of a plane, say x-z,
// are the pair sums (xm + xp) at k - 1 and k + 1: the row kernel forms (xm + xp) and (ym + yp)
// once per cell for the axis ring and shifts them for the diagonals (me4_row_avx512vl).
struct Me4Sums {
  float ring1, ring2, diag;
};
inline Me4Sums me4_sums(const float* p, long sx, long sy, int k) {
  const float* xm = p - sx;
  const float* xp = p + sx;
  const float* ym = p - sy;
  const float* yp = p + sy;
  Me4Sums s;
  s.ring1 = ((xm[k] + xp[k]) + (ym[k] + yp[k])) + (p[k - 1] + p[k + 1]);
  s.ring2 = ((p[k - 2 * sx] + p[k + 2 * sx]) + (p[k - 2 * sy] + p[k + 2 * sy])) + (p[k - 2] + p[k + 2]);
  const float dxy = (xm[k - sy] + xp[k - sy]) + (xm[k + sy] + xp[k + sy]);
  const float dxz = (xm[k - 1] + xp[k - 1]) + (xm[k + 1] + xp[k + 1]);
  const float dyz = (ym[k - 1] + yp[k - 1]) + (ym[k + 1] + yp[k + 1]);
  s.diag = (dxy + dxz) + dyz;
  return s;
}

// One z row of the me4 bulk update where the CPU has no AVX-512VL (me4_row_avx512vl below, the
// same arithmetic, where it has). Cloned for AVX2 and the baseline: wider vectors divide its 25
// loads per cell. No AVX-512 clone: the rows start 4 floats apart from a cache line (260-float
// rows), so nearly every 64-byte load of the 25 splits over two lines, and on Zen 4 the 256-bit
// clone ran the whole step about 10 % faster (docs/benchmarks.md). Each cell's arithmetic is the
// same in every clone (no FMA contraction, -ffp-contract=off), so the bits do not depend on the CPU.
__attribute__((target_clones("avx2", "default")))
void me4_row(const float* __restrict p, float* __restrict q, long sx, long sy, int nk, Operator::Me4 c) {
#pragma omp simd
  for (int k = 0; k < nk; ++k) {
    const Me4Sums s = me4_sums(p, sx, sy, k);
    q[k] = ((c.c0 * p[k] - q[k]) + (c.c1 * s.ring1 + c.c2 * s.ring2)) + c.c3 * s.diag;
  }
}

// The blend into the layer on cells [k0, k1) of a row that me4_row has updated:
// q += theta (srl - me4), theta = max(theta_xy, theta_z[k]); srl - me4 needs p^n alone.
// AVX2 like me4_row.
__attribute__((target_clones("avx2", "default")))
void blend_row(const float* __restrict p, float* __restrict q, long sx, long sy, int k0, int k1,
               const float* __restrict theta_z, float theta_xy, float d0, float d1, float d2, float d3) {
#pragma omp simd
  for (int k = k0; k < k1; ++k) {
    const Me4Sums s = me4_sums(p, sx, sy, k);
    const float theta = theta_xy > theta_z[k] ? theta_xy : theta_z[k];
    q[k] += theta * (((d0 * p[k] + d1 * s.ring1) + d2 * s.ring2) + d3 * s.diag);
  }
}

#if defined(__x86_64__)
#define CLATTER_ME4_AVX512VL 1

// The me4 row kernel for CPUs with AVX-512VL, register-blocked along z. Of the 25 points per cell
// it loads each of the 13 rows once, at k: the z neighbours k +- 1, k +- 2 of the centre row and
// of the pair sums (xm + xp) and (ym + yp) are lane shifts (valignd) of the vectors at k - 8, k and
// k + 8, kept from step to step. Shifting the pair sums rather than the four rows they add makes
// the x-z and y-z diagonals one addition each: 21 additions and 8 shifts per vector, not 25 and 12
// (the bulk is not bound by memory bandwidth; the step 5 % faster, docs/benchmarks.md).
// 256-bit vectors: 512-bit ones split over two cache lines at every load (260-float rows),
// and AVX-512VL brings the 32 vector registers that keep the windows and coefficients out of
// memory (GCC 12 spilled with AVX2's 16). The arithmetic of each cell is me4_row's and
// blend_row's, operation for operation (no FMA), so the bits are the same.
using Vec = __m256;
#define CLATTER_AVX512VL_FN __attribute__((target("avx512vl"), always_inline)) inline

// r[a, a + 8) with the lanes that fall outside r[lo, hi) not read (0): the ends of a row.
template <bool kEdge>
CLATTER_AVX512VL_FN Vec load8(const float* r, long a, long lo, long hi) {
  if constexpr (!kEdge) {
    return _mm256_loadu_ps(r + a);
  } else {
    const long from = std::max(0L, lo - a), to = std::min(8L, hi - a);
    const unsigned lanes = to > from ? ((1u << to) - 1u) & ~((1u << from) - 1u) : 0u;
    return _mm256_maskz_loadu_ps(static_cast<__mmask8>(lanes), r + a);
  }
}
CLATTER_AVX512VL_FN Vec add(Vec a, Vec b) { return _mm256_add_ps(a, b); }
CLATTER_AVX512VL_FN Vec mul(Vec a, Vec b) { return _mm256_mul_ps(a, b); }
// The lanes [n, n + 8) of (lo, hi), lo first.
template <int n>
CLATTER_AVX512VL_FN Vec lanes_from(Vec hi, Vec lo) {
  return _mm256_castsi256_ps(_mm256_alignr_epi32(_mm256_castps_si256(hi), _mm256_castps_si256(lo), n));
}

// A row around k: r[k - 8, k) and r[k, k + 8).
struct ZWindow {
  Vec prev, cur;
};
struct ZNeighbours {
  Vec m2, m1, c, p1, p2;  // r at k - 2, k - 1, k, k + 1, k + 2
};
template <bool kTwo>
CLATTER_AVX512VL_FN ZNeighbours slide(ZWindow& w, Vec next) {
  ZNeighbours z;
  z.c = w.cur;
  z.m1 = lanes_from<7>(w.cur, w.prev);
  z.p1 = lanes_from<1>(next, w.cur);
  if constexpr (kTwo) {
    z.m2 = lanes_from<6>(w.cur, w.prev);
    z.p2 = lanes_from<2>(next, w.cur);
  } else {
    z.m2 = z.p2 = z.c;
  }
  w.prev = w.cur;
  w.cur = next;
  return z;
}

// The blend into the layer along one row: theta = max(theta_xy, theta_z[k]); cells [plain_lo,
// plain_hi) are known to have theta = 0, and vectors within them skip it.
struct Me4Blend {
  const float* theta_z;
  float theta_xy;
  float d0, d1, d2, d3;  // srl - me4
  long plain_lo, plain_hi;
};

__attribute__((target("avx512vl")))
void me4_row_avx512vl(const float* __restrict p, float* __restrict q, long sx, long sy, int nk, Operator::Me4 c,
                      const Me4Blend& blend) {
  const float* const xm = p - sx;
  const float* const xp = p + sx;
  const float* const ym = p - sy;
  const float* const yp = p + sy;
  const long end = nk, row_end = end + 2;  // cells, and the row's values with its z neighbours
  auto start = [&](const float* r) __attribute__((target("avx512vl"))) {
    return ZWindow{load8<true>(r, -8, -2, row_end), load8<true>(r, 0, -2, row_end)};
  };
  auto start_sum = [&](const float* a, const float* b) __attribute__((target("avx512vl"))) {
    const ZWindow wa = start(a), wb = start(b);
    return ZWindow{add(wa.prev, wb.prev), add(wa.cur, wb.cur)};
  };
  ZWindow wc = start(p), wsx = start_sum(xm, xp), wsy = start_sum(ym, yp);
  const Vec c0 = _mm256_set1_ps(c.c0), c1 = _mm256_set1_ps(c.c1), c2 = _mm256_set1_ps(c.c2), c3 = _mm256_set1_ps(c.c3);
  const Vec d0 = _mm256_set1_ps(blend.d0), d1 = _mm256_set1_ps(blend.d1), d2 = _mm256_set1_ps(blend.d2),
            d3 = _mm256_set1_ps(blend.d3), theta_xy = _mm256_set1_ps(blend.theta_xy);
  // Cells k .. k + 7. The two streams that come from memory (p^n two planes ahead, and p^{n-1} ->
  // p^{n+1}) are fetched 1.5 KiB ahead: the hardware's prefetch alone left the loop waiting on
  // them (the step at 256^3 took 17 % longer without).
  auto step = [&](long k, auto edge, auto blended) __attribute__((target("avx512vl"), always_inline)) {
    constexpr bool kEdge = decltype(edge)::value;
    if constexpr (!kEdge) {
      constexpr long kAheadFloats = 384;
      _mm_prefetch(reinterpret_cast<const char*>(p + 2 * sx + k + kAheadFloats), _MM_HINT_T0);
      _mm_prefetch(reinterpret_cast<const char*>(q + k + kAheadFloats), _MM_HINT_T0);
    }
    const ZNeighbours z = slide<true>(wc, load8<kEdge>(p, k + 8, -2, row_end));
    const ZNeighbours pair_x = slide<false>(wsx, add(load8<kEdge>(xm, k + 8, -2, row_end), load8<kEdge>(xp, k + 8, -2, row_end)));
    const ZNeighbours pair_y = slide<false>(wsy, add(load8<kEdge>(ym, k + 8, -2, row_end), load8<kEdge>(yp, k + 8, -2, row_end)));
    auto at = [&](const float* r) __attribute__((target("avx512vl"), always_inline)) {
      return load8<kEdge>(r, k, 0, end);
    };
    const Vec ring1 = add(add(pair_x.c, pair_y.c), add(z.m1, z.p1));
    const Vec ring2 = add(add(add(at(p - 2 * sx), at(p + 2 * sx)), add(at(p - 2 * sy), at(p + 2 * sy))), add(z.m2, z.p2));
    const Vec dxy = add(add(at(xm - sy), at(xp - sy)), add(at(xm + sy), at(xp + sy)));
    const Vec dxz = add(pair_x.m1, pair_x.p1);
    const Vec dyz = add(pair_y.m1, pair_y.p1);
    const Vec diag = add(add(dxy, dxz), dyz);
    Vec out = add(add(_mm256_sub_ps(mul(c0, z.c), at(q)), add(mul(c1, ring1), mul(c2, ring2))), mul(c3, diag));
    if constexpr (decltype(blended)::value) {
      const Vec theta = _mm256_max_ps(theta_xy, at(blend.theta_z));  // theta_xy > theta_z ? theta_xy : theta_z
      const __mmask8 on = _mm256_cmp_ps_mask(theta, _mm256_setzero_ps(), _CMP_GT_OQ);
      const Vec srl_minus_me4 = add(add(add(mul(d0, z.c), mul(d1, ring1)), mul(d2, ring2)), mul(d3, diag));
      out = _mm256_mask_add_ps(out, on, out, mul(theta, srl_minus_me4));
    }
    if constexpr (!kEdge)
      _mm256_storeu_ps(q + k, out);
    else
      _mm256_mask_storeu_ps(q + k, static_cast<__mmask8>((1u << std::min(8L, end - k)) - 1u), out);
  };
  using Yes = std::true_type;
  using No = std::false_type;
  // Whole vectors whose next vector (k + 8 .. k + 15) is still within the row's values; the blend
  // is skipped on the vectors within [plain_lo, plain_hi) only.
  long k = 0;
  const long whole_end = row_end - 16;
  for (; k <= whole_end && !(k >= blend.plain_lo && k + 8 <= blend.plain_hi); k += 8) step(k, No{}, Yes{});
  for (; k <= whole_end && k + 8 <= blend.plain_hi; k += 8) step(k, No{}, No{});
  for (; k <= whole_end; k += 8) step(k, No{}, Yes{});
  for (; k < end; k += 8) step(k, Yes{}, Yes{});
}
#endif

// One z row of the srl bulk update, cloned the same way. Neighbours are summed in mirror pairs.
__attribute__((target_clones("avx512f", "avx2", "default")))
void srl_row(const float* __restrict p, float* __restrict q, long sx, long sy, int nk, float c1, float l2) {
  const float* __restrict xm = p - sx;
  const float* __restrict xp = p + sx;
  const float* __restrict ym = p - sy;
  const float* __restrict yp = p + sy;
#pragma omp simd
  for (int k = 0; k < nk; ++k)
    q[k] = (c1 * p[k] - q[k]) + l2 * (((xm[k] + xp[k]) + (ym[k] + yp[k])) + (p[k - 1] + p[k + 1]));
}

bool portable_rows = false;

}  // namespace

void use_portable_row_kernels(bool on) { portable_rows = on; }

Engine::Engine(const Operator& op, HaloExchange& halo)
    : op_(op),
      halo_(halo),
      now_(op.layout().size(), 0.0f),
      next_(op.layout().size(), 0.0f),
      pml_(op.pml().make_state()),
      cut_body_(op.cut_cells().index.size()),
      cut_old_(op.cut_cells().index.size()) {
  const Layout& layout = op.layout();
  const Box& inner = op.inner_box();
  const auto& index = op.cut_cells().index;  // in storage order, so plane by plane
  interior_cut_start_.assign(static_cast<std::size_t>(std::max(0, inner.hi[0] - inner.lo[0])) + 1, 0);
  for (std::size_t c = 0; c < index.size(); ++c) {
    const long s = index[c];
    const std::array<int, 3> cell{static_cast<int>(s / layout.stride[0]) - Layout::kHalo + layout.owned.lo[0],
                                  static_cast<int>(s % layout.stride[0] / layout.stride[1]) - Layout::kHalo + layout.owned.lo[1],
                                  static_cast<int>(s % layout.stride[1]) - Layout::kHalo + layout.owned.lo[2]};
    if (!inner.contains(cell)) {
      other_cut_.push_back(c);
      continue;
    }
    interior_cut_.push_back(c);
    ++interior_cut_start_[static_cast<std::size_t>(cell[0] - inner.lo[0]) + 1];
  }
  for (std::size_t n = 1; n < interior_cut_start_.size(); ++n) interior_cut_start_[n] += interior_cut_start_[n - 1];
  start(op.problem().field);
}

void Engine::start(int field) {
  if ((field == 0) != (op_.problem().field == 0))
    throw std::logic_error("Engine::start: monopole and body fields do not mix");
  field_ = field;
  std::fill(now_.begin(), now_.end(), 0.0f);
  std::fill(next_.begin(), next_.end(), 0.0f);
  op_.pml().reset(pml_);
  const auto& body_all = op_.cut_cells().body_all;
  for (std::size_t c = 0; c < body_all.size(); ++c)
    cut_body_[c] = field > 0 ? body_all[c][static_cast<std::size_t>(field - 1)] : 0.0f;
}

void Engine::step(double t_s) {
  halo_.start(now_.data());
  keep_cut_cell_old();
  fill_z_mirror_ghosts();
  const float psi = static_cast<float>(pulse(t_s, op_.problem().h_s));
  {
    Stage s("interior");
    update_bulk(op_.inner_box(), true, psi);
  }
  {
    Stage s("halo wait");
    halo_.finish();
  }
  {
    Stage s("shell, PML, body");
    fill_mirror_ghosts();
    for (const auto& b : op_.shell_boxes()) update_bulk(b);
    op_.pml().update(pml_, now_.data(), next_.data(), op_.inner_box());
    update_cut_cells(psi, other_cut_.data(), other_cut_.data() + other_cut_.size());
    if (!op_.point_source().empty()) {
      const double h = op_.problem().h_s, dt = op_.problem().dt_s;
      const float smooth = static_cast<float>((pulse(t_s - dt, h) + 10.0 * pulse(t_s, h) + pulse(t_s + dt, h)) / 12.0);
      add_point_source(psi, smooth);
    }
  }
  now_.swap(next_);
}

// Ghost layers -1 and -2 across the z mirror plane of the block's own rows := parity x layers 0
// and 1, before the interior: they need no halo, and the interior then covers k = 0 and 1 too.
void Engine::fill_z_mirror_ghosts() {
  if (!op_.problem().grid.octant || op_.layout().owned.lo[2] != 0) return;
  const Layout& layout = op_.layout();
  const Box& o = layout.owned;
  const float sign = static_cast<float>(field_parity(field_, 2));
  for (int i = o.lo[0]; i < o.hi[0]; ++i)
    for (int j = o.lo[1]; j < o.hi[1]; ++j) {
      float* row = now_.data() + layout.at(i, j, 0);
      row[-1] = sign * row[0];
      row[-2] = sign * row[1];
    }
}

// Ghost layers -1 and -2 across each mirror plane := parity x layers 0 and 1. Runs after the halo
// has arrived and covers the whole storage extent of the other axes, axis after axis, so ghosts
// across two planes (read by face-diagonal points) are mirrored twice and halo cells mirror too.
// The z ghosts of the block's own rows are already there (fill_z_mirror_ghosts); only the rows
// of the halo are left for the z pass.
void Engine::fill_mirror_ghosts() {
  if (!op_.problem().grid.octant) return;
  const Layout& layout = op_.layout();
  const Box& o = layout.owned;
  const int h = Layout::kHalo;
  for (int a = 0; a < 3; ++a) {
    if (o.lo[a] != 0) continue;
    const float sign = static_cast<float>(field_parity(field_, a));
    Box plane;
    for (int b = 0; b < 3; ++b) {
      plane.lo[b] = o.lo[b] - h;
      plane.hi[b] = o.hi[b] + h;
    }
    plane.lo[a] = 0;
    plane.hi[a] = 1;
    const long s = layout.stride[a];
    for (int i = plane.lo[0]; i < plane.hi[0]; ++i)
      for (int j = plane.lo[1]; j < plane.hi[1]; ++j) {
        if (a == 2 && i >= o.lo[0] && i < o.hi[0] && j >= o.lo[1] && j < o.hi[1]) continue;  // done before
        for (int k = plane.lo[2]; k < plane.hi[2]; ++k) {
          const long here = layout.at(i, j, k);
          for (int g = 1; g <= h; ++g)  // ghost -g mirrors layer g - 1
            now_[static_cast<std::size_t>(here - g * s)] = sign * now_[static_cast<std::size_t>(here + (g - 1) * s)];
        }
      }
  }
}

void Engine::keep_cut_cell_old() {
  const auto& index = op_.cut_cells().index;
  for (std::size_t c = 0; c < index.size(); ++c) cut_old_[c] = next_[static_cast<std::size_t>(index[c])];
}

void Engine::update_bulk(const Box& box, bool interior, float psi) {
  if (box.empty()) return;
  if (op_.problem().scheme == Scheme::me4)
    update_bulk_me4(box, interior, psi);
  else
    update_bulk_srl(box, interior, psi);
}

// The interior's cut cells of plane i, which the bulk has just overwritten, while the planes they
// read are in cache: after the bulk, from memory again, they took 6 % of the me4 step at 256^3.
void Engine::update_interior_cut_cells(int i, float psi) {
  const auto n = static_cast<std::size_t>(i - op_.inner_box().lo[0]);
  update_cut_cells(psi, interior_cut_.data() + interior_cut_start_[n], interior_cut_.data() + interior_cut_start_[n + 1]);
}

void Engine::update_bulk_srl(const Box& box, bool interior, float psi) {
  const Layout& layout = op_.layout();
  const int nk = box.hi[2] - box.lo[2];
  for (int i = box.lo[0]; i < box.hi[0]; ++i) {
    for (int j = box.lo[1]; j < box.hi[1]; ++j) {
      const long row = layout.at(i, j, box.lo[2]);
      srl_row(now_.data() + row, next_.data() + row, layout.stride[0], layout.stride[1], nk, op_.c1(), op_.lambda2());
      if (interior) op_.pml().update_z_rows(pml_, now_.data(), next_.data(), i, j, j + 1);
    }
    if (interior) update_interior_cut_cells(i, psi);
  }
}

void Engine::update_bulk_me4(const Box& box, bool interior, float psi) {
  const Layout& layout = op_.layout();
  const long sx = layout.stride[0], sy = layout.stride[1];
  const auto c = op_.me4();
  const auto& blend = op_.blend();
  const float* blend_z = blend[2].data() + box.lo[2];
  const int nk = box.hi[2] - box.lo[2];
  std::vector<std::pair<int, int>> z_runs;  // the runs [k0, k1) of this box within the blend
  for (int k = 0; k < nk; ++k)
    if (blend_z[k] > 0.0f) {
      if (z_runs.empty() || z_runs.back().second != k) z_runs.push_back({k, k});
      ++z_runs.back().second;
    }
  // srl - me4 at a cell, from p^n alone (p^{n-1} cancels): the blend's correction.
  const float d0 = op_.c1() - c.c0, d1 = op_.lambda2() - c.c1, d2 = -c.c2, d3 = -c.c3;
#if CLATTER_ME4_AVX512VL
  static const bool avx512vl = __builtin_cpu_supports("avx512vl");
  // Rows outside the x-y blend skip it on the first stretch of cells between z runs (the runs
  // are at the rows' ends; the kernel blends any other run exactly, only it does not skip).
  long plain_lo = 0, plain_hi = nk;
  if (!z_runs.empty() && z_runs[0].first == 0) {
    plain_lo = z_runs[0].second;
    plain_hi = z_runs.size() > 1 ? z_runs[1].first : nk;
  } else if (!z_runs.empty()) {
    plain_hi = z_runs[0].first;
  }
#endif
  // Plane after plane, no y tiles: with the z neighbours in registers and p^n two planes ahead and
  // p^{n-1} prefetched, tiles that kept five planes' rows in L2 (256 KiB) made the step 11 % slower
  // at 256^3 (their row pieces restart the memory streams, the PML z rows' state's too).
  // The PML's z layers at both ends of the rows go with them (interior): their 6-cell pieces of
  // rows, swept alone, would fetch whole lines of p^n from memory a second time.
  for (int i = box.lo[0]; i < box.hi[0]; ++i) {
    for (int j = box.lo[1]; j < box.hi[1]; ++j) {
      const long row = layout.at(i, j, box.lo[2]);
      const float blend_xy = std::max(blend[0][static_cast<std::size_t>(i)], blend[1][static_cast<std::size_t>(j)]);
#if CLATTER_ME4_AVX512VL
      if (avx512vl && !portable_rows) {
        const bool all = blend_xy > 0.0f;
        me4_row_avx512vl(now_.data() + row, next_.data() + row, sx, sy, nk, c,
                         {blend_z, blend_xy, d0, d1, d2, d3, all ? 0 : plain_lo, all ? 0 : plain_hi});
      } else
#endif
      {
        me4_row(now_.data() + row, next_.data() + row, sx, sy, nk, c);
        if (blend_xy > 0.0f) {
          blend_row(now_.data() + row, next_.data() + row, sx, sy, 0, nk, blend_z, blend_xy, d0, d1, d2, d3);
        } else {
          for (const auto& [k0, k1] : z_runs)
            blend_row(now_.data() + row, next_.data() + row, sx, sy, k0, k1, blend_z, 0.0f, d0, d1, d2, d3);
        }
      }
      if (interior) op_.pml().update_z_rows(pml_, now_.data(), next_.data(), i, j, j + 1);
    }
    if (interior) update_interior_cut_cells(i, psi);
  }
}

void Engine::update_cut_cells(float psi, const std::size_t* first, const std::size_t* last) {
  const CutCells& cut = op_.cut_cells();
  const long sx = op_.layout().stride[0], sy = op_.layout().stride[1];
  const float* p = now_.data();
  for (const std::size_t* slot = first; slot != last; ++slot) {
    const std::size_t c = *slot;
    const long i = cut.index[c];
    const auto& a = cut.alpha[c];
    const float pc = p[i];
    const float s = ((a[0] * (p[i - sx] - pc) + a[1] * (p[i + sx] - pc)) + (a[2] * (p[i - sy] - pc) + a[3] * (p[i + sy] - pc))) +
                    (a[4] * (p[i - 1] - pc) + a[5] * (p[i + 1] - pc));
    next_[static_cast<std::size_t>(i)] = (2.0f * pc - cut_old_[c]) + cut.gain[c] * s + cut_body_[c] * psi;
  }
}

void Engine::add_point_source(float psi, float psi_smooth) {
  for (const auto& s : op_.point_source())
    next_[static_cast<std::size_t>(s.index)] += s.smoothed * psi_smooth + s.now * psi;
}

}  // namespace clatter::kernels::fdtd
