// The FDTD engine stepped without MPI: against the exact monopole field, and split into two blocks
// joined through the halo interface, against the one-block run bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

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
