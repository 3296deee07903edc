// clatter-bench: the machine's memory bandwidth (the roofline every kernel is compared with) and
// the cost of the foundation's own layers. Metrics are explained in docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <numeric>
#include <vector>

#include "core/stage_log.hpp"
#include "io/h5.hpp"
#include "kernels/fdtd/float_mode.hpp"
#include "kernels/fdtd/engine.hpp"
#include "kernels/fdtd/kirchhoff.hpp"
#include "kernels/fdtd/operator.hpp"
#include "kernels/pulse.hpp"

namespace {

// STREAM (McCalpin) kernels on arrays far larger than the last-level cache. Bytes counted the
// STREAM way: what the loop reads plus what it writes, without write-allocate traffic.
void BM_StreamCopy(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(n, 1.0), c(n, 0.0);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) c[i] = a[i];
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * 2 * n * sizeof(double)));
}

void BM_StreamTriad(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(a.data());
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * 3 * n * sizeof(double)));
}

// psi(t; h) evaluations per second: it is called once per boundary cell per time step in the FDTD.
void BM_Pulse(benchmark::State& state) {
  std::vector<double> t(4096);
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = -3e-4 + 6e-4 * static_cast<double>(i) / 4096.0;
  for (auto _ : state) {
    double sum = 0;
    for (double x : t) sum += clatter::kernels::pulse(x, 1e-4);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * t.size()));
}

// Cost of one timed stage (enter + leave) inside a parent, as a time loop would use it.
void BM_StageEnterLeave(benchmark::State& state) {
  clatter::StageLog log;
  clatter::Stage parent("solve", log);
  for (auto _ : state) {
    clatter::Stage step("step", log);
    benchmark::DoNotOptimize(&step);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

// One float32 dataset written through io::File, committed (fsync + rename) every iteration.
void BM_H5WriteCommit(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<float> data(n);
  std::iota(data.begin(), data.end(), 0.0f);
  const std::string path = (std::filesystem::temp_directory_path() / "clatter-bench-write.h5").string();
  for (auto _ : state) {
    auto f = clatter::io::File::create(path);
    clatter::io::write_dataset<float>(f, "/p", data, {n}, "Pa");
    f.commit();
  }
  std::filesystem::remove(path);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * n * sizeof(float)));
}

// One FDTD time step on one rank, no MPI: N^3 cells (full domain, 6-cell PML, the A = 0.5 m
// ellipsoid of the PAN bank at N = 256 with 1 cm cells), field 1, scheme srl (second argument 0) or
// me4 (1). Bytes are counted at the pressure-only minimum of 12 per cell update (read p^n and
// p^{n-1}, write p^{n+1}), the same for both schemes.
void BM_FdtdStep(benchmark::State& state) {
  namespace fdtd = clatter::kernels::fdtd;
  const int n = static_cast<int>(state.range(0));
  fdtd::Problem p;
  p.grid = {{n, n, n}, 2.56 / n, false, 6};
  p.dt_s = 0.5 * p.grid.dx_m / (p.c_m_s * 1.7320508075688772);
  p.body = {0.5, 0.35, 0.2};
  p.field = 1;
  p.scheme = state.range(1) == 0 ? fdtd::Scheme::srl : fdtd::Scheme::me4;
  state.SetLabel(fdtd::scheme_name(p.scheme));
  const fdtd::FlushSubnormals flush;
  const fdtd::Operator op(p, p.grid.all());
  clatter::NoHaloExchange halo;
  fdtd::Engine engine(op, halo);
  double t = -2 * p.h_s;
  for (auto _ : state) {
    engine.step(t);
    t += p.dt_s;
  }
  const auto cells = static_cast<int64_t>(n) * n * n;
  state.SetItemsProcessed(state.iterations() * cells);
  state.SetBytesProcessed(state.iterations() * cells * 12);
  state.counters["bytes_per_cell_stored"] =
      static_cast<double>(op.counts().bytes) / static_cast<double>(cells);
}

// One PAN listener through the Kirchhoff surface at the paper's resolution (an octant staircase
// ball of radius 0.5 m + 3 cells of 6.5 mm, its 8 mirror images, a record of 2571 samples at
// 96 kHz): the cost that dominates a PAN task (docs/pan.md). The series are arbitrary but nonzero;
// the cost does not depend on them. Items: element-image-samples summed. Arg 2: a point through
// the cigar proxy's surface, the ball cut by its box (0.5, 0.025, 0.025) m + 4 cells.
void BM_KirchhoffPoint(benchmark::State& state) {
  namespace fdtd = clatter::kernels::fdtd;
  fdtd::Problem p;
  const double dx = 0.0065;
  p.grid = {{99, 99, 99}, dx, true, 6};
  p.dt_s = 1.0 / 96000;
  p.field = 1;
  const int samples = 2571;
  fdtd::SurfaceShape shape{0.5 + 3 * dx};
  if (state.range(0) == 2) shape.half_box_m = {0.5 + 4 * dx, 0.025 + 4 * dx, 0.025 + 4 * dx};
  fdtd::SurfaceField f = fdtd::empty_surface(p, shape, samples, -2e-4);
  for (std::size_t i = 0; i < f.p.size(); ++i) {
    f.p[i] = static_cast<float>(std::sin(0.001 * static_cast<double>(i)));
    f.dpdn[i] = static_cast<float>(std::cos(0.0013 * static_cast<double>(i)));
  }
  const bool far = state.range(0) == 1;
  state.SetLabel(far ? "far field" : state.range(0) == 2 ? "point at 1.2 m, the cigar's surface" : "point at 1.2 m");
  const std::array<double, 3> d{0.48, 0.6, 0.64};
  for (auto _ : state) {
    auto s = far ? fdtd::far_field(f, d) : fdtd::pressure_at(f, {1.2 * d[0], 1.2 * d[1], 1.2 * d[2]});
    benchmark::DoNotOptimize(s.value.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(f.elements.size()) * 8 * samples);
  state.counters["elements"] = static_cast<double>(f.elements.size());
}

// B points at the radii 0.7-3 m along one direction heard in one pass over the surface (a PAN
// direction's radii), 2571 samples: S = 0 a full-domain surface (an entry of eight octants, a mesh
// without mirror symmetry like Table 1's plate: the staircase ball of 0.5 m + 3 cells cut by a
// plate's box, +-0.086 m in z; one image), S = 1 BM_KirchhoffPoint's octant ball (8 images).
// Items: element-image-samples summed over the points.
void BM_KirchhoffPoints(benchmark::State& state) {
  namespace fdtd = clatter::kernels::fdtd;
  fdtd::Problem p;
  const double dx = 0.0065;
  const bool octant = state.range(1) == 1;
  p.grid = octant ? fdtd::Grid{{99, 99, 99}, dx, true, 6} : fdtd::Grid{{198, 198, 198}, dx, false, 6};
  p.dt_s = 1.0 / 96000;
  p.field = 1;
  const int samples = 2571;
  fdtd::SurfaceShape shape{0.5 + 3 * dx};
  if (!octant) shape.half_box_m = {0.5 + 4 * dx, 0.5 + 4 * dx, 0.06 + 4 * dx};
  fdtd::SurfaceField f = fdtd::empty_surface(p, shape, samples, -2e-4);
  for (std::size_t i = 0; i < f.p.size(); ++i) {
    f.p[i] = static_cast<float>(std::sin(0.001 * static_cast<double>(i)));
    f.dpdn[i] = static_cast<float>(std::cos(0.0013 * static_cast<double>(i)));
  }
  const auto batch = static_cast<std::size_t>(state.range(0));
  const std::array<double, 3> d{0.48, 0.6, 0.64};
  std::vector<std::array<double, 3>> points;
  for (std::size_t b = 0; b < batch; ++b) {
    const double r = 0.7 + 2.3 * static_cast<double>(b) / 8;
    points.push_back({r * d[0], r * d[1], r * d[2]});
  }
  for (auto _ : state) {
    auto s = fdtd::pressure_at(f, points);
    benchmark::DoNotOptimize(s.front().value.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(f.elements.size() * batch) * (octant ? 8 : 1) * samples);
  state.counters["elements"] = static_cast<double>(f.elements.size());
}

}  // namespace

BENCHMARK(BM_KirchhoffPoints)->ArgsProduct({{1, 2, 3, 5, 9}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FdtdStep)->ArgsProduct({{128, 256}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StreamCopy)->Arg(1 << 25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StreamTriad)->Arg(1 << 25)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_KirchhoffPoint)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Pulse);
BENCHMARK(BM_StageEnterLeave);
BENCHMARK(BM_H5WriteCommit)->Arg(1 << 18)->Arg(1 << 24)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
