// The FDTD engine stepped without MPI: against the exact monopole field, and split into two blocks
// joined through the halo interface, against the one-block run bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "core/block_layout.hpp"
#include "core/halo_exchange.hpp"
#include "kernels/fdtd/engine.hpp"
#include "kernels/fdtd/float_mode.hpp"
#include "kernels/fdtd/operator.hpp"
#include "kernels/fdtd/recorder.hpp"
#include "kernels/pulse.hpp"

using namespace clatter;
namespace fdtd = clatter::kernels::fdtd;

namespace {

// A monopole in a 0.48 m box with cells of dx_m and the PML 6 cells thick, driven by a pulse a few
// cells wide (c h = 3.4 cm), so the grid's dispersion is what the error measures.
fdtd::Problem monopole_problem(double dx_m) {
  fdtd::Problem p;
  const int n = static_cast<int>(std::lround(0.48 / dx_m));
  p.grid = {{n, n, n}, dx_m, false, 6};
  p.dt_s = 0.5 * dx_m / p.c_m_s;
  p.h_s = 1e-4;
  p.field = 0;
  return p;
}

// A small ellipsoid in a full domain with its PML: bulk, cut cells and layer all take part.
fdtd::Problem body_problem(bool octant) {
  fdtd::Problem p;
  p.grid = {{octant ? 12 : 24, octant ? 12 : 24, octant ? 12 : 24}, 0.01, octant, 4};
  p.dt_s = 0.5 * 0.01 / p.c_m_s;
  p.h_s = 1e-4;
  p.body = {0.06, 0.045, 0.03};
  p.field = 1;
  return p;
}

int first_step(const fdtd::Problem& p) { return static_cast<int>(std::ceil(2.0 * p.h_s / p.dt_s - 1e-9)); }

}  // namespace

namespace {

// Relative L2 error per listener of a one-block solve, from the start of the pulse (-2h) to 1.5 ms.
std::vector<double> monopole_errors(double dx_m, const std::vector<std::array<double, 3>>& listeners) {
  const fdtd::Problem p = monopole_problem(dx_m);
  const int i_time_zero = first_step(p), n_samples = i_time_zero + static_cast<int>(std::lround(1.5e-3 / p.dt_s));
  const fdtd::FlushSubnormals flush;
  const fdtd::Operator op(p, p.grid.all());
  NoHaloExchange halo;
  fdtd::Engine engine(op, halo);
  fdtd::Recorder recorder(p, listeners, engine.layout(), n_samples);
  for (int n = 0; n < n_samples; ++n) {
    recorder.record(n, engine.pressure());
    if (n + 1 < n_samples) engine.step((n - i_time_zero) * p.dt_s);
  }
  const auto series = fdtd::interpolate_listeners(recorder.stencils(), n_samples, {recorder.pack()});
  const std::size_t ns = static_cast<std::size_t>(n_samples);
  std::vector<double> errors;
  for (std::size_t l = 0; l < listeners.size(); ++l) {
    const auto& x = listeners[l];
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    double num = 0, den = 0;
    for (std::size_t k = 0; k < ns; ++k) {
      const double t = (static_cast<double>(k) - i_time_zero) * p.dt_s;
      const double want = kernels::monopole_pressure(r, t, p.h_s, p.c_m_s, p.rho_kg_m3), got = series[l * ns + k];
      num += (got - want) * (got - want);
      den += want * want;
    }
    errors.push_back(den > 0 ? std::sqrt(num / den) : 1.0);
  }
  return errors;
}

}  // namespace

TEST(FdtdEngine, MonopoleMatchesTheExactFieldAndConvergesWithoutMpi) {
  // On an axis, off every axis, and near a plane; all well inside the PML.
  const std::vector<std::array<double, 3>> listeners{{0.1, 0.0, 0.0}, {0.07, 0.06, 0.05}, {0.0, -0.12, 0.03}};
  const auto coarse = monopole_errors(0.01, listeners), fine = monopole_errors(0.005, listeners);
  for (std::size_t l = 0; l < listeners.size(); ++l) {
    const double order = std::log2(coarse[l] / fine[l]);
    std::printf("listener %zu: relative L2 error %.4f at dx = 1 cm, %.4f at 0.5 cm: observed order %.2f\n", l,
                coarse[l], fine[l], order);
    EXPECT_LT(fine[l], 0.03) << "listener " << l;
    EXPECT_GT(order, 1.5) << "listener " << l;
  }
}

namespace {

// Two blocks that split the grid along x, joined in one process: the x faces are copied between the
// two engines' storage through the layouts' own face regions, the other faces are the grid's
// boundary. Both sides' p^n are final when the first side of a step starts, and the second side's
// start would already see the first's p^{n+1}: so the first start of each step copies both ways.
struct SerialPair {
  std::array<const fdtd::Layout*, 2> layout{};
  std::array<const fdtd::Engine*, 2> engine{};
  long long starts = 0;

  void copy(int from, int to) const {
    const int side_from = from == 0 ? 1 : 0, side_to = to == 0 ? 1 : 0;
    const StorageRegion src = layout[from]->face(0, side_from, false), dst = layout[to]->face(0, side_to, true);
    const float* in = engine[from]->pressure();
    // Writing another block's halo is what an exchange is for; the engine hands out p^n read-only.
    auto* out = const_cast<float*>(engine[to]->pressure());
    for (int i = 0; i < src.count[0]; ++i)
      for (int j = 0; j < src.count[1]; ++j)
        for (int k = 0; k < src.count[2]; ++k) {
          const long s = (src.start[0] + i) * layout[from]->stride[0] + (src.start[1] + j) * layout[from]->stride[1] +
                         src.start[2] + k;
          const long d = (dst.start[0] + i) * layout[to]->stride[0] + (dst.start[1] + j) * layout[to]->stride[1] +
                         dst.start[2] + k;
          out[d] = in[s];
        }
  }
};

class SerialHalo final : public HaloExchange {
 public:
  explicit SerialHalo(SerialPair& pair) : pair_(pair) {}
  void start(float*) override {
    if (pair_.starts++ % 2 != 0) return;
    pair_.copy(0, 1);
    pair_.copy(1, 0);
  }
  void finish() override {}

 private:
  SerialPair& pair_;
};

// Steps p one block and as two blocks split at x = split; every owned cell of the two must carry
// the one block's bits after every step.
void expect_split_identical(const fdtd::Problem& p, int split) {
  const fdtd::FlushSubnormals flush;
  const fdtd::Operator whole_op(p, p.grid.all());
  NoHaloExchange none;
  fdtd::Engine whole(whole_op, none);
  const Box all = p.grid.all();
  const Box low{all.lo, {split, all.hi[1], all.hi[2]}}, high{{split, all.lo[1], all.lo[2]}, all.hi};
  const fdtd::Operator low_op(p, low), high_op(p, high);
  ASSERT_GT(whole_op.counts().cut, 0);
  EXPECT_EQ(low_op.counts().cut + high_op.counts().cut, whole_op.counts().cut);
  SerialPair pair;
  SerialHalo low_halo(pair), high_halo(pair);
  fdtd::Engine a(low_op, low_halo), b(high_op, high_halo);
  pair.layout = {&low_op.layout(), &high_op.layout()};
  pair.engine = {&a, &b};
  const int i_time_zero = first_step(p);
  double peak = 0;
  for (int n = 0; n < 3 * i_time_zero + 40; ++n) {
    const double t_s = (n - i_time_zero) * p.dt_s;
    whole.step(t_s);
    a.step(t_s);
    b.step(t_s);
    long long differ = 0;
    for (const auto* part : {&a, &b}) {
      const Box& o = part->layout().owned;
      for (int i = o.lo[0]; i < o.hi[0]; ++i)
        for (int j = o.lo[1]; j < o.hi[1]; ++j)
          for (int k = o.lo[2]; k < o.hi[2]; ++k) {
            const float x = part->value({i, j, k}), y = whole.value({i, j, k});
            if (std::memcmp(&x, &y, sizeof x) != 0) ++differ;
            peak = std::max(peak, double(std::abs(y)));
          }
    }
    ASSERT_EQ(differ, 0) << "cells differing after step " << n;
  }
  EXPECT_GT(peak, 0) << "the pulse must have driven the field";
}

}  // namespace

TEST(FdtdEngine, TwoBlocksThroughTheHaloInterfaceEqualOneBlockBitForBit) {
  expect_split_identical(body_problem(false), 11);
}

TEST(FdtdEngine, TwoOctantBlocksThroughTheHaloInterfaceEqualOneBlockBitForBit) {
  expect_split_identical(body_problem(true), 5);
}

namespace {

// The me4 bulk update and its blend into the PML written as a plain scalar triple loop, from the
// formulas of docs/fdtd.md with the sums grouped in mirror pairs as documented:
//   p+ = ((c0 p - p-) + (c1 ring1 + c2 ring2)) + c3 diag,
//   then, where theta = max(theta_x, theta_y, theta_z) > 0, p+ += theta (((d0 p + d1 ring1) + d2 ring2) + d3 diag).
// p and q are whole storage arrays (halo included) of `layout`; q holds p^{n-1} and gets p^{n+1}.
void naive_me4_bulk(const fdtd::Operator& op, const std::vector<float>& p, std::vector<float>& q) {
  const fdtd::Layout& layout = op.layout();
  const auto c = op.me4();
  const float d0 = op.c1() - c.c0, d1 = op.lambda2() - c.c1, d2 = -c.c2, d3 = -c.c3;
  const auto& blend = op.blend();
  const Box b = op.problem().grid.interior().intersect(layout.owned);
  auto at = [&](int i, int j, int k) { return p[static_cast<std::size_t>(layout.at(i, j, k))]; };
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        const float ring1 = ((at(i - 1, j, k) + at(i + 1, j, k)) + (at(i, j - 1, k) + at(i, j + 1, k))) +
                            (at(i, j, k - 1) + at(i, j, k + 1));
        const float ring2 = ((at(i - 2, j, k) + at(i + 2, j, k)) + (at(i, j - 2, k) + at(i, j + 2, k))) +
                            (at(i, j, k - 2) + at(i, j, k + 2));
        const float dxy = (at(i - 1, j - 1, k) + at(i + 1, j - 1, k)) + (at(i - 1, j + 1, k) + at(i + 1, j + 1, k));
        const float dxz = (at(i - 1, j, k - 1) + at(i + 1, j, k - 1)) + (at(i - 1, j, k + 1) + at(i + 1, j, k + 1));
        const float dyz = (at(i, j - 1, k - 1) + at(i, j + 1, k - 1)) + (at(i, j - 1, k + 1) + at(i, j + 1, k + 1));
        const float diag = (dxy + dxz) + dyz;
        const float centre = at(i, j, k);
        float& out = q[static_cast<std::size_t>(layout.at(i, j, k))];
        out = ((c.c0 * centre - out) + (c.c1 * ring1 + c.c2 * ring2)) + c.c3 * diag;
        const float theta = std::max({blend[0][static_cast<std::size_t>(i)], blend[1][static_cast<std::size_t>(j)],
                                      blend[2][static_cast<std::size_t>(k)]});
        if (theta > 0.0f) out += theta * (((d0 * centre + d1 * ring1) + d2 * ring2) + d3 * diag);
      }
}

// Octant mode: ghost layers -1, -2 across each mirror plane := layers 0, 1 (the monopole is even),
// axis after axis over the whole storage extent, as docs/fdtd.md describes.
void mirror_ghosts(const fdtd::Problem& problem, const fdtd::Layout& layout, std::vector<float>& p) {
  if (!problem.grid.octant) return;
  const auto e = layout.extent();
  for (int a = 0; a < 3; ++a)
    for (int s0 = 0; s0 < e[0]; ++s0)
      for (int s1 = 0; s1 < e[1]; ++s1)
        for (int s2 = 0; s2 < e[2]; ++s2) {
          const std::array<int, 3> s{s0, s1, s2};
          const int g = fdtd::Layout::kHalo - s[a];  // ghost -g for storage index kHalo - g
          if (g < 1 || g > fdtd::Layout::kHalo) continue;
          const long here = s0 * layout.stride[0] + s1 * layout.stride[1] + s2;
          p[static_cast<std::size_t>(here)] = p[static_cast<std::size_t>(here + (2 * g - 1) * layout.stride[a])];
        }
}

// A monopole problem's operator and engine on one block, p^n random everywhere (halo, PML and
// ghosts included): where the naive-loop tests below start.
struct RandomStart {
  fdtd::FlushSubnormals flush;
  fdtd::Operator op;
  NoHaloExchange halo;
  fdtd::Engine engine;
  RandomStart(const fdtd::Problem& p, std::uint32_t state) : op(p, p.grid.all()), engine(op, halo) {
    auto* now = const_cast<float*>(engine.pressure());  // the test seeds the field it steps
    for (std::size_t x = 0; x < op.layout().size(); ++x) {
      state = state * 1664525u + 1013904223u;
      now[x] = static_cast<float>(state >> 8) / 16777216.0f - 0.5f;
    }
  }
};

// Steps a monopole problem from random p^n and p^{n-1} with the Engine and compares every bulk
// cell (the point source's cells aside) bit for bit with naive_me4_bulk after each step.
void expect_me4_bulk_matches_naive(const fdtd::Problem& p, bool all_blended = false) {
  ASSERT_EQ(p.scheme, fdtd::Scheme::me4);
  ASSERT_EQ(p.field, 0);
  for (int a = 0; a < 3; ++a) ASSERT_EQ(fdtd::field_parity(0, a), 1);
  RandomStart start(p, 12345u);  // one step makes the random p^n p^{n-1}
  const fdtd::Operator& op = start.op;
  fdtd::Engine& engine = start.engine;
  const fdtd::Layout& layout = op.layout();
  const std::size_t size = layout.size();
  std::vector<float> old(engine.pressure(), engine.pressure() + size);
  const double dt = p.dt_s;
  engine.step(-2 * p.h_s);
  std::vector<bool> skip(size, false);
  for (const auto& s : op.point_source()) skip[static_cast<std::size_t>(s.index)] = true;
  const Box b = p.grid.interior();
  long long compared = 0, blended = 0;
  for (int n = 1; n <= 4; ++n) {
    std::vector<float> cur(engine.pressure(), engine.pressure() + size);
    mirror_ghosts(p, layout, cur);
    std::vector<float> want = old;
    naive_me4_bulk(op, cur, want);
    engine.step(-2 * p.h_s + n * dt);
    long long differ = 0;
    for (int i = b.lo[0]; i < b.hi[0]; ++i)
      for (int j = b.lo[1]; j < b.hi[1]; ++j)
        for (int k = b.lo[2]; k < b.hi[2]; ++k) {
          const auto x = static_cast<std::size_t>(layout.at(i, j, k));
          if (skip[x]) continue;
          const float got = engine.value({i, j, k});
          if (std::memcmp(&got, &want[x], sizeof got) != 0) {
            if (differ++ < 5)
              ADD_FAILURE() << "step " << n << " cell (" << i << ", " << j << ", " << k << "): engine " << got
                            << ", naive " << want[x];
          }
          ++compared;
          if (n == 1 && std::max({op.blend()[0][static_cast<std::size_t>(i)], op.blend()[1][static_cast<std::size_t>(j)],
                                  op.blend()[2][static_cast<std::size_t>(k)]}) > 0.0f)
            ++blended;
        }
    ASSERT_EQ(differ, 0) << "bulk cells differing after step " << n;
    old.swap(cur);
  }
  EXPECT_EQ(compared, 4 * (b.cells() - static_cast<long long>(op.point_source().size())));
  EXPECT_GT(blended, 0) << "the blend region must take part";
  if (!all_blended) {
    EXPECT_LT(blended, compared / 4) << "cells outside the blend must take part";
  }
}

fdtd::Problem me4_monopole(std::array<int, 3> n, bool octant) {
  fdtd::Problem p;
  p.grid = {n, 0.01, octant, 4};
  p.dt_s = 0.5 * 0.01 / p.c_m_s;
  p.h_s = 1e-4;
  p.field = 0;
  p.scheme = fdtd::Scheme::me4;
  return p;
}

}  // namespace

namespace {

// Rows per plane not a multiple of 4, rows whose length is no multiple of the vector width, one
// shorter than a vector, an octant's mirror ghosts and shell.
void expect_me4_cases_match_naive() {
  expect_me4_bulk_matches_naive(me4_monopole({28, 34, 46}, false));        // bulk 20 x 26 x 38
  expect_me4_bulk_matches_naive(me4_monopole({26, 30, 20}, false), true);  // bulk 18 x 22 x 12, all blended
  expect_me4_bulk_matches_naive(me4_monopole({21, 27, 25}, true));   // bulk 17 x 23 x 21, mirrors
}

}  // namespace

// The bulk kernel this CPU runs (register-blocked where it has AVX-512VL, the blend in the same
// pass) against the scalar formula.
TEST(FdtdEngine, Me4BulkMatchesANaiveLoopBitForBit) { expect_me4_cases_match_naive(); }

// The portable rows (me4_row + blend_row, AVX2 or baseline), which CPUs without AVX-512VL run,
// against the same scalar formula; on a CPU without AVX-512VL this repeats the test above.
TEST(FdtdEngine, Me4PortableRowsMatchANaiveLoopBitForBit) {
  struct Portable {  // switched back however the test ends
    Portable() { fdtd::use_portable_row_kernels(true); }
    ~Portable() { fdtd::use_portable_row_kernels(false); }
  } portable;
  expect_me4_cases_match_naive();
}

namespace {

// The PML written as plain scalar loops over global indices, from the formulas of pml.cpp (kept
// here as the reference any rewrite of the layer's kernels must reproduce bit for bit): graded
// sigma, face velocities of each damped axis from the gradient of p^n (faces on the grid's outer
// boundary stay 0), then per layer cell the damped axes' split parts explicitly and the undamped
// axes through the 7-point Laplacian, summed x, y, z in that order.
class NaivePml {
 public:
  NaivePml(const fdtd::Problem& p, const fdtd::Layout& layout) : p_(p), layout_(layout) {
    const fdtd::Grid& g = p.grid;
    const double dt = p.dt_s, dx = g.dx_m, rho = p.rho_kg_m3, c = p.c_m_s, l = g.pml;
    const double sigma_max = -4.0 * c * std::log(p.pml_reflection) / (2.0 * l * dx);
    auto depth = [&](int a, double position) {
      double d = position - (g.n[a] - l);
      if (!g.octant) d = std::max(d, l - position);
      return std::max(d, 0.0);
    };
    auto sigma = [&](double d) { return sigma_max * std::pow(d / l, 3); };
    for (int a = 0; a < 3; ++a) {
      for (int i = 0; i < g.n[a]; ++i) {
        const double s = sigma(depth(a, i + 0.5)), den = 1.0 + 0.5 * s * dt;
        cdec_[a].push_back(static_cast<float>((1.0 - 0.5 * s * dt) / den));
        cgain_[a].push_back(static_cast<float>(rho * c * c * dt / dx / den));
        damped_[a].push_back(depth(a, i + 0.5) > 0);
      }
      for (int f = 0; f <= g.n[a]; ++f) {
        const double s = sigma(depth(a, f)), den = 1.0 + 0.5 * s * dt;
        fdec_[a].push_back(static_cast<float>((1.0 - 0.5 * s * dt) / den));
        fgain_[a].push_back(static_cast<float>(dt / (rho * dx) / den));
      }
      const std::size_t cells = static_cast<std::size_t>(g.n[0]) * g.n[1] * g.n[2];
      v_[a].assign(static_cast<std::size_t>(g.n[0] + 1) * (g.n[1] + 1) * (g.n[2] + 1), 0.0f);
      now_[a].assign(cells, 0.0f);
      old_[a].assign(cells, 0.0f);
    }
    l2_ = static_cast<float>(p.courant() * p.courant());
  }

  int mask(int i, int j, int k) const {
    return (damped_[0][static_cast<std::size_t>(i)] ? 1 : 0) | (damped_[1][static_cast<std::size_t>(j)] ? 2 : 0) |
           (damped_[2][static_cast<std::size_t>(k)] ? 4 : 0);
  }

  // p: p^n (storage of the layout, mirror ghosts filled); q: p^{n-1} -> p^{n+1} on the layer's cells.
  void step(const std::vector<float>& p, std::vector<float>& q) {
    const auto& n = p_.grid.n;
    auto at = [&](int i, int j, int k) { return p[static_cast<std::size_t>(layout_.at(i, j, k))]; };
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < n[0] + (a == 0); ++i)
        for (int j = 0; j < n[1] + (a == 1); ++j)
          for (int k = 0; k < n[2] + (a == 2); ++k) {
            const std::array<int, 3> f{i, j, k};
            const int g = f[a];
            if (g == 0 || g == n[a]) continue;  // the rigid wall behind the layer, or outside the grid
            std::array<int, 3> below = f;
            --below[a];
            if (!damped_[a][static_cast<std::size_t>(g)] && !damped_[a][static_cast<std::size_t>(g - 1)]) continue;
            float& v = v_[a][face(i, j, k)];
            v = fdec_[a][static_cast<std::size_t>(g)] * v -
                fgain_[a][static_cast<std::size_t>(g)] * (at(i, j, k) - at(below[0], below[1], below[2]));
          }
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) {
          const int d = mask(i, j, k);
          if (d == 0) continue;
          const std::array<int, 3> c{i, j, k};
          const std::size_t cell = (static_cast<std::size_t>(i) * n[1] + j) * n[2] + k;
          float split = 0.0f, pairs = 0.0f;
          int undamped = 0;
          for (int a = 0; a < 3; ++a) {
            std::array<int, 3> lo = c, hi = c;
            --lo[a];
            ++hi[a];
            if (d & (1 << a)) {
              std::array<int, 3> up = c;
              ++up[a];
              const float vl = v_[a][face(c[0], c[1], c[2])], vh = v_[a][face(up[0], up[1], up[2])];
              const float now = now_[a][cell];
              const float next = cdec_[a][static_cast<std::size_t>(c[a])] * now -
                                 cgain_[a][static_cast<std::size_t>(c[a])] * (vh - vl);
              split += (next - 2.0f * now) + old_[a][cell];
              old_[a][cell] = next;
            } else {
              pairs += at(lo[0], lo[1], lo[2]) + at(hi[0], hi[1], hi[2]);
              ++undamped;
            }
          }
          const float centre = 2.0f * static_cast<float>(undamped), pc = at(i, j, k);
          float& out = q[static_cast<std::size_t>(layout_.at(i, j, k))];
          out = (2.0f * pc - out) + l2_ * (pairs - centre * pc) + split;
        }
    for (int a = 0; a < 3; ++a) now_[a].swap(old_[a]);
  }

 private:
  std::size_t face(int i, int j, int k) const {
    const auto& n = p_.grid.n;
    return (static_cast<std::size_t>(i) * (n[1] + 1) + j) * (n[2] + 1) + k;
  }

  fdtd::Problem p_;
  fdtd::Layout layout_;
  float l2_ = 0;
  std::array<std::vector<float>, 3> cdec_, cgain_, fdec_, fgain_, v_, now_, old_;
  std::array<std::vector<bool>, 3> damped_;
};

// Steps a monopole problem from a random p^n with the Engine and compares every cell of the layer
// bit for bit with NaivePml after each step (the layer's state evolving in both).
void expect_pml_matches_naive(const fdtd::Problem& p) {
  ASSERT_EQ(p.field, 0);
  RandomStart start(p, 987654u);
  const fdtd::Operator& op = start.op;
  fdtd::Engine& engine = start.engine;
  const fdtd::Layout& layout = op.layout();
  const std::size_t size = layout.size();
  NaivePml naive(p, layout);
  std::vector<float> old(size, 0.0f);  // the Engine starts at rest: p^{n-1} = 0
  long long compared = 0;
  std::array<long long, 8> by_mask{};
  for (int n = 0; n < 8; ++n) {
    std::vector<float> cur(engine.pressure(), engine.pressure() + size);
    mirror_ghosts(p, layout, cur);
    std::vector<float> want = old;
    naive.step(cur, want);
    engine.step(-2 * p.h_s + n * p.dt_s);
    long long differ = 0;
    const auto& g = p.grid.n;
    for (int i = 0; i < g[0]; ++i)
      for (int j = 0; j < g[1]; ++j)
        for (int k = 0; k < g[2]; ++k) {
          const int d = naive.mask(i, j, k);
          if (d == 0) continue;
          const auto x = static_cast<std::size_t>(layout.at(i, j, k));
          const float got = engine.value({i, j, k});
          if (std::memcmp(&got, &want[x], sizeof got) != 0 && differ++ < 5)
            ADD_FAILURE() << "step " << n << " cell (" << i << ", " << j << ", " << k << ") damped " << d << ": engine "
                          << got << ", naive " << want[x];
          ++compared;
          ++by_mask[static_cast<std::size_t>(d)];
        }
    ASSERT_EQ(differ, 0) << "layer cells differing after step " << n;
    old.swap(cur);
  }
  EXPECT_GT(compared, 0);
  for (int d = 1; d < 8; ++d)
    if (!p.grid.octant || d == 1 || d == 2 || d == 4 || d == 7) {
      EXPECT_GT(by_mask[static_cast<std::size_t>(d)], 0) << "region kind " << d;
    }
}

fdtd::Problem pml_monopole(std::array<int, 3> n, bool octant, int pml, fdtd::Scheme scheme) {
  fdtd::Problem p = me4_monopole(n, octant);
  p.grid.pml = pml;
  p.scheme = scheme;
  return p;
}

}  // namespace

// The layer's kernels (faces, split parts, the z slabs however they are swept) against the scalar
// formula, full domain and octant, both schemes, layers 4 and 6 cells thick.
TEST(FdtdEngine, PmlMatchesANaiveLoopBitForBit) {
  expect_pml_matches_naive(pml_monopole({28, 34, 46}, false, 4, fdtd::Scheme::me4));
  expect_pml_matches_naive(pml_monopole({30, 26, 41}, false, 6, fdtd::Scheme::me4));
  expect_pml_matches_naive(pml_monopole({26, 30, 36}, false, 6, fdtd::Scheme::srl));
  expect_pml_matches_naive(pml_monopole({21, 27, 25}, true, 4, fdtd::Scheme::me4));
  expect_pml_matches_naive(pml_monopole({22, 19, 30}, true, 6, fdtd::Scheme::srl));
}
