// The acoustic transfer of one mode (kernels/transfer/mode_transfer.hpp) on the default bank's
// sphere mesh, by k a and the data's angular order, and the evaluation of a stored multipole per
// listener by its order (docs/benchmarks.md "Acoustic transfer").
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <cstdlib>
#include <numbers>

#include "io/modal_bank.hpp"
#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/transfer/mesh_transfer.hpp"
#include "kernels/transfer/mode_transfer.hpp"
#include "kernels/transfer/special_functions.hpp"
#include "kernels/transfer/surface_interpolation.hpp"
#include "tests/unit/quadratic_meshes.hpp"

namespace {
using namespace clatter::kernels;
constexpr double kA = 0.5773502691896258;

struct SphereData {
  std::vector<std::array<double, 3>> nodes;
  std::vector<std::array<std::int32_t, 6>> faces;
};

// The sphere meshed at h [m] (0.164: the default bank's sphere entry), once per h.
const SphereData& sphere(double h_m) {
  static std::map<double, SphereData> cache;
  auto [it, fresh] = cache.try_emplace(h_m);
  if (!fresh) return it->second;
  it->second = [h_m] {
    const auto m = fem::mesh_ellipsoid({{kA, kA, kA}, h_m});
    SphereData d;
    for (Eigen::Index i = 0; i < m.mesh.nodes_m.cols(); ++i)
      d.nodes.push_back({m.mesh.nodes_m(0, i), m.mesh.nodes_m(1, i), m.mesh.nodes_m(2, i)});
    for (const auto& f : m.boundary) d.faces.push_back({f[0], f[1], f[2], f[3], f[4], f[5]});
    return d;
  }();
  return it->second;
}

// args: k a, n of the normal displacement Re Y_n^1 (n = 0: the pulsating sphere), and the mesh's
// h in mm (the surface size: 164 is the default bank's sphere, 82 has 4x the surface nodes).
void BM_TransferSphereMode(benchmark::State& state) {
  const double ka = static_cast<double>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  const auto& s = sphere(static_cast<double>(state.range(2)) * 1e-3);
  std::vector<double> shape;
  std::vector<std::complex<double>> y(static_cast<std::size_t>(transfer::harmonic_count(n)));
  for (const auto& p : s.nodes) {
    const Eigen::Vector3d d = Eigen::Vector3d(p[0], p[1], p[2]).normalized();
    transfer::spherical_harmonics(n, d.z(), std::atan2(d.y(), d.x()), y.data());
    const double v = y[static_cast<std::size_t>(transfer::harmonic_index(n, n > 0 ? 1 : 0))].real();
    for (int c = 0; c < 3; ++c) shape.push_back(v * d(c));
  }
  const transfer::TransferSettings settings;
  const auto u = transfer::mesh_displacement({kA, kA, kA}, s.nodes, s.faces, shape);
  const double spacing = transfer::surface_node_spacing_m(s.nodes, s.faces);
  transfer::ModeTransfer t;
  for (auto _ : state) {
    t = transfer::solve_mode_transfer({kA, kA, kA}, ka / kA * settings.sound_speed_m_s, spacing, u, settings);
    benchmark::DoNotOptimize(t.expansion.coefficients.data());
  }
  state.counters["sources"] = t.sources;
  state.counters["fit_points"] = t.fit_points;
  state.counters["order"] = t.expansion.order;
  state.counters["classes"] = t.classes;
  state.counters["attempts"] = t.attempts;
  state.counters["residual"] = t.boundary_residual;
  state.counters["surface_faces"] = static_cast<double>(s.faces.size());
}

// A mode of a real bank: CLATTER_BANK=path (a modal bank), args: entry, mode. Skipped without it.
void BM_TransferBankMode(benchmark::State& state) {
  const char* path = std::getenv("CLATTER_BANK");
  if (!path) {
    state.SkipWithError("set CLATTER_BANK to a modal bank");
    return;
  }
  static const auto bank = clatter::io::read_modal_bank(path);
  const auto& e = bank.entries.at(static_cast<std::size_t>(state.range(0)));
  const auto mode = static_cast<std::size_t>(state.range(1));
  const std::size_t per_mode = 3 * e.surface_nodes_m.size();
  const auto u = transfer::mesh_displacement(e.axes_m, e.surface_nodes_m, e.surface_faces,
                                             std::span<const double>(e.shapes.data() + mode * per_mode, per_mode));
  transfer::TransferSettings settings;
  transfer::ModeTransfer t;
  for (auto _ : state)
    t = transfer::solve_mode_transfer(e.axes_m, 2 * std::numbers::pi * e.frequencies_hz[mode],
                                      transfer::surface_node_spacing_m(e.surface_nodes_m, e.surface_faces), u, settings);
  state.counters["sources"] = t.sources;
  state.counters["fit_points"] = t.fit_points;
  state.counters["attempts"] = t.attempts;
  state.counters["residual"] = t.boundary_residual;
  state.counters["normal_fraction"] = t.normal_fraction;
  state.counters["kc"] = t.expansion.k_rad_m * e.axes_m[2];
}

// One mode of the 26 cm ceramic plate, 6 mm thick (mesh edges ~5 mm), through the general-shape
// solver (kernels/transfer/mesh_transfer.hpp): args: f in Hz, the ceiling on unknowns. A made-up
// bending mode at the Kirchhoff plate's wavenumber (E 70 GPa, rho 2400 kg/m^3, nu 0.22).
void BM_TransferPlateMode(benchmark::State& state) {
  static const auto plate = clatter::test::plate(0.13, 0.006, 26);
  const double omega = 2 * std::numbers::pi * static_cast<double>(state.range(0));
  const double stiffness = 70e9 * std::pow(0.006, 3) / (12 * (1 - 0.22 * 0.22)), mass_per_area = 2400 * 0.006;
  const double kb = std::pow(omega * omega * mass_per_area / stiffness, 0.25);
  std::vector<double> shape;
  for (const auto& p : plate.nodes_m)
    shape.insert(shape.end(), {0, 0, 1e-3 * std::cos(kb * (0.8 * p[0] + 0.6 * p[1]) + 0.3) * std::cos(0.7 * kb * p[1])});
  transfer::MeshTransferOptions options;
  options.max_unknowns = static_cast<int>(state.range(1));
  transfer::MeshTransfer t;
  for (auto _ : state) {
    t = transfer::solve_mesh_mode_transfer(plate.nodes_m, plate.faces, shape, omega, transfer::TransferSettings{}, options);
    benchmark::DoNotOptimize(t.expansion.coefficients.data());
  }
  state.counters["sources"] = t.sources;
  state.counters["dipoles"] = t.dipoles;
  state.counters["cells"] = t.fit_points;
  state.counters["residual"] = t.boundary_residual;
  state.counters["order"] = t.expansion.order;
}

// Evaluation of |p| at one listener from a stored expansion of the given order.
void BM_MultipoleEvaluate(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  transfer::Multipole m{50.0, order, std::vector<std::complex<double>>(static_cast<std::size_t>(transfer::harmonic_count(order)), {1e-3, 2e-3})};
  const Eigen::Vector3d x(1.3, -0.4, 2.1);
  for (auto _ : state) benchmark::DoNotOptimize(std::abs(m.pressure(x)));
  state.counters["bytes"] = 16.0 * transfer::harmonic_count(order);
}

}  // namespace

BENCHMARK(BM_TransferSphereMode)->ArgsProduct({{1, 10, 20, 40, 70, 90}, {2}, {164}})->Args({40, 8, 164})
    ->Args({90, 8, 164})->Args({20, 2, 82})->Args({70, 2, 82})
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TransferBankMode)->Args({0, 0})->Args({0, 5})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_TransferPlateMode)->Args({2000, 1500})->Args({8000, 1500})->Args({20000, 1500})->Args({8000, 800})
    ->Args({8000, 3000})->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_MultipoleEvaluate)->Arg(4)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMicrosecond);
