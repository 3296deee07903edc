// clatter-transfer-settings: the acoustic transfer of stored modes again, under other layout
// settings, to measure what a setting costs and buys (docs/transfer.md "Cost"). Serial: no FEM,
// the modes come from a modal bank (the synthesizer's serial HDF5 reader).
//   clatter-transfer-settings BANK ENTRY MODE[,MODE...] [KEY=VALUE ...]
// KEY: rim_spacing_per_depth, rim_inner_fraction, points_per_source, sources_per_wavelength,
// data_spacing_factor (the surface's node spacing scaled, which caps the sources' and fit points'
// spacing). Prints one line per mode: seconds, sources, fit points, boundary residual, normal fraction.
#include <chrono>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/modal_bank.hpp"
#include "kernels/transfer/mode_transfer.hpp"
#include "kernels/transfer/surface_interpolation.hpp"

namespace {
using namespace clatter;
namespace kt = kernels::transfer;

int run(int argc, char** argv) {
  if (argc < 4) throw std::invalid_argument("usage: clatter-transfer-settings BANK ENTRY MODE[,MODE...] [KEY=VALUE ...]");
  const model::ModalBank bank = io::read_modal_bank(argv[1]);
  const auto& entry = bank.entries.at(static_cast<std::size_t>(std::stoul(argv[2])));
  kt::TransferSettings settings = bank.header.transfer;
  double data_factor = 1;
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
    else if (key == "data_spacing_factor") data_factor = value;
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
    std::printf("mode %zu %.1f Hz: %.2f s, %d sources, %d fit points, residual %.2e, normal fraction %.2f, order %d\n", mode,
                entry.frequencies_hz[mode], s, t.sources, t.fit_points, t.boundary_residual, t.normal_fraction,
                t.expansion.order);
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
