// clatter-transfer-settings: the acoustic transfer of stored modes again, under other layout
// settings, to measure what a setting costs and buys (docs/transfer.md "Cost"). Serial: no FEM,
// the modes come from a modal bank (the synthesizer's serial HDF5 reader).
//   clatter-transfer-settings BANK ENTRY MODE[,MODE...] [KEY=VALUE ...]
// KEY: rim_aspect, rim_thin_ratio, residual_target, rim_spacing_per_depth, rim_inner_fraction, points_per_source, sources_per_wavelength,
// data_spacing_factor (the surface's node spacing scaled, which caps the sources' and fit points'
// spacing), where (1: the residual by zone from the face centre to the rim). Prints one line per
// mode: seconds, sources, fit points, boundary residual, normal fraction.
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/modal_bank.hpp"
#include "kernels/transfer/mode_transfer.hpp"
#include "kernels/transfer/surface_interpolation.hpp"

namespace {
using namespace clatter;
namespace kt = kernels::transfer;

// where=1: the boundary residual by zone, from the face centre to the rim, on a fine grid in the
// rim layout's angles (sin t: the distance from the thin axis as a share of the rim's), so that a
// layout's weak spot shows.
void residual_by_zone(const std::array<double, 3>& axes_m, double omega, const kt::TransferSettings& settings,
                      const kt::SurfaceDisplacement& u, const kt::ModeTransfer& t) {
  const std::vector<double> edges{0, 0.5, 0.8, 0.9, 0.95, 0.99, 0.999, 1.0001};
  const kt::SurfacePoints points = kt::rim_grid(axes_m, std::vector<int>(160, 80));
  const double k = omega / settings.sound_speed_m_s, scale = settings.air_density_kg_m3 * omega * omega;
  const auto fields = kt::class_fields(k, t.solution->fit, t.solution->layout, points, kt::FieldParts::kNormalDerivative);
  std::vector<double> err(edges.size() - 1, 0.0), norm(edges.size() - 1, 0.0), largest_u(edges.size() - 1, 0.0);
  double total = 0;
  std::vector<std::complex<double>> p, dp;
  for (int s = 0; s < 8; ++s) {
    kt::field_at_mirror(fields, s, p, dp);
    const auto values = u(points, s);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d x = points.position_m[i];
      const double r = std::hypot(x.y() / axes_m[1], x.z() / axes_m[2]);
      std::size_t z = 0;
      while (z + 2 < edges.size() && r >= edges[z + 1]) ++z;
      const double g = scale * values[i].dot(kt::mirror(points.normal[i], s)), w = points.weight_m2[i];
      largest_u[z] = std::max(largest_u[z], values[i].norm());
      err[z] += w * std::norm(dp[i] - g);
      norm[z] += w * g * g;
      total += w * g * g;
    }
  }
  for (std::size_t z = 0; z + 1 < edges.size(); ++z)
    std::printf("  rim share %.3f-%.3f: residual %.2e of the zone's data, %.2e of the whole; data share %.3f; largest |u| %.3g\n",
                edges[z], edges[z + 1], std::sqrt(err[z] / std::max(norm[z], 1e-300)), std::sqrt(err[z] / total),
                std::sqrt(norm[z] / total), largest_u[z]);
}

int run(int argc, char** argv) {
  if (argc < 4) throw std::invalid_argument("usage: clatter-transfer-settings BANK ENTRY MODE[,MODE...] [KEY=VALUE ...]");
  const model::ModalBank bank = io::read_modal_bank(argv[1]);
  const auto& entry = bank.entries.at(static_cast<std::size_t>(std::stoul(argv[2])));
  kt::TransferSettings settings = bank.header.transfer;
  double data_factor = 1;
  bool where = false;
  for (int i = 4; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto eq = arg.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("expected KEY=VALUE: " + arg);
    const std::string key = arg.substr(0, eq);
    const double value = std::stod(arg.substr(eq + 1));
    if (key == "rim_spacing_per_depth") settings.rim_spacing_per_depth = value;
    else if (key == "rim_inner_fraction") settings.rim_inner_fraction = value;
    else if (key == "points_per_source") settings.points_per_source = value;
    else if (key == "sources_per_wavelength") settings.sources_per_wavelength = value;
    else if (key == "rim_aspect") settings.rim_aspect = value;
    else if (key == "rim_thin_ratio") settings.rim_thin_ratio = value;
    else if (key == "residual_target") settings.residual_target = value;
    else if (key == "data_spacing_factor") data_factor = value;
    else if (key == "where") where = value != 0;
    else throw std::invalid_argument("unknown key " + key);
  }
  const double spacing = data_factor * kt::surface_node_spacing_m(entry.surface_nodes_m, entry.surface_faces);
  std::stringstream modes(argv[3]);
  for (std::string item; std::getline(modes, item, ',');) {
    const auto mode = static_cast<std::size_t>(std::stoul(item));
    const std::size_t per_mode = 3 * entry.surface_nodes_m.size();
    const std::span<const double> shape(entry.shapes.data() + mode * per_mode, per_mode);
    const auto u = kt::mesh_displacement(entry.axes_m, entry.surface_nodes_m, entry.surface_faces, shape);
    const auto t0 = std::chrono::steady_clock::now();
    const auto t = kt::solve_mode_transfer(entry.axes_m, 2 * std::numbers::pi * entry.frequencies_hz[mode], spacing, u, settings);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // FNV-1a of the expansion's bytes: whether two builds give the same bits.
    std::uint64_t digest = 1469598103934665603ull;
    for (const auto& c : t.expansion.coefficients) {
      unsigned char bytes[sizeof(c)];
      std::memcpy(bytes, &c, sizeof(c));
      for (unsigned char b : bytes) digest = (digest ^ b) * 1099511628211ull;
    }
    std::printf("mode %zu %.1f Hz: %.2f s, %d sources, %d fit points, residual %.2e, normal fraction %.2f, order %d, "
                "%d classes, %d attempts, coefficients' digest %016llx\n", mode, entry.frequencies_hz[mode], s, t.sources, t.fit_points,
                t.boundary_residual, t.normal_fraction, t.expansion.order, t.classes, t.attempts, static_cast<unsigned long long>(digest));
    if (where) residual_by_zone(entry.axes_m, 2 * std::numbers::pi * entry.frequencies_hz[mode], settings, u, t);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clatter-transfer-settings: %s\n", e.what());
    return 2;
  }
}
