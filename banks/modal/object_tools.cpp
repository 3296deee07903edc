#include "banks/modal/object_tools.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "banks/modal/modal_tools.hpp"
#include "core/errors.hpp"
#include "io/object_bank.hpp"
#include "kernels/transfer/multipole.hpp"

namespace clatter::jobs {
namespace {

const model::ObjectEntry& entry_of(const model::ObjectBank& bank, const std::string& path, std::size_t entry) {
  if (entry >= bank.entries.size())
    throw InputError(fmt::format("--entry {}: {} holds entries 0-{}", entry, path, bank.entries.size() - 1));
  return bank.entries[entry];
}

}  // namespace

std::string object_bank_info(const std::string& path, std::optional<std::size_t> entry) {
  const model::ObjectBank bank = io::read_object_bank(path);
  if (entry) {
    const auto& e = entry_of(bank, path, *entry);
    return fmt::format("entry {}: {} from {}, {} modes\n", *entry, e.key, e.source, e.modal.modes()) + modes_csv(e.modal);
  }
  const auto& h = bank.header;
  const double file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::string out = fmt::format("{}: object bank (format {} v{}), {} objects, {:.3f} MB on disk\n", path,
                                io::kObjectBankFormat, io::kObjectBankFormatVersion, bank.entries.size(), file_mb);
  out += fmt::format("  settings:   modes f_1 .. {} Hz (whole multiplets); h = shear wavelength at f_max / {}, at most the "
                     "thinnest part / {}; clusters split by > {}; tolerance {}, residuals <= {}; {} rank(s) per entry; "
                     "a scene's objects taken below {} Hz\n",
                     h.f_max_hz, h.elements_per_wavelength, h.elements_through_thickness, h.solve.cluster_gap,
                     h.solve.tolerance, h.solve.residual_limit, h.ranks_per_task, h.proxy_above_hz);
  out += fmt::format("  transfer:   {}; air c = {} m/s, rho = {} kg/m^3\n", h.transfer.method, h.transfer.sound_speed_m_s,
                     h.transfer.air_density_kg_m3);
  out += "  entry  key                          material  modes  f_1 [Hz]   last [Hz]  dofs     h [m]     thinnest [m]  "
         "max res  transfer: order, max boundary res (normal fraction > 0.3)  time [s]  mesh\n";
  for (std::size_t i = 0; i < bank.entries.size(); ++i) {
    const auto& oe = bank.entries[i];
    const auto& e = oe.modal;
    const double worst = e.modes() ? *std::max_element(e.relative_residuals.begin(), e.relative_residuals.end()) : 0;
    const auto& t = e.transfer;
    const int order = e.modes() ? *std::max_element(t.order.begin(), t.order.end()) : 0;
    double boundary = 0;
    for (std::size_t k = 0; k < e.modes(); ++k)
      if (t.normal_fraction[k] > model::kNormalFractionPromised) boundary = std::max(boundary, t.boundary_residual[k]);
    out += fmt::format("  {:<5}  {:<27}  {:<8}  {:<5}  {:<9.2f}  {:<9.2f}  {:<7}  {:<8.3g}  {:<12.3g}  {:.1e}  {:<3} {:.1e}  "
                       "{:<8.1f}  {}\n",
                       i, oe.key, oe.material.name, e.modes(), e.modes() ? e.frequencies_hz.front() : 0.0,
                       e.modes() ? e.frequencies_hz.back() : 0.0, e.mesh.dofs, e.mesh.edge_length_m, oe.min_thickness_m,
                       worst, order, boundary, e.cost.total_s, oe.source);
    out += fmt::format("         clusters (frequencies within the gap; size x count): {}; mass {:.4g} kg, radius {:.4g} m\n",
                       group_sizes(e.cluster), oe.mass_kg, oe.radius_m);
    out += "         band: " + band_guarantee(e, "") + "\n";
  }
  const auto& sw = bank.sweep;
  out += fmt::format("  sweep:      {} of {} entries in the bank, {} failed, {} missing\n", sw.tasks_done(), sw.tasks_total,
                     sw.failed.size(), sw.missing.size());
  for (const auto& f : sw.failed) out += "    failed:  " + f + "\n";
  for (const auto& x : sw.missing) out += "    missing: " + x + "\n";
  return out;
}

std::string object_probe_csv(const std::string& path, std::size_t entry, const std::array<double, 3>& point_m) {
  const model::ObjectBank bank = io::read_object_bank(path);
  const auto& oe = entry_of(bank, path, entry);
  const Eigen::Vector3d x(point_m[0], point_m[1], point_m[2]);
  if (!(x.norm() > oe.radius_m))
    throw InputError(fmt::format("--point {},{},{}: {:.4g} m from the centre of mass; the transfer holds beyond the "
                                 "object's radius {:.4g} m",
                                 point_m[0], point_m[1], point_m[2], x.norm(), oe.radius_m));
  const auto& e = oe.modal;
  std::string out = "mode,frequency_hz,abs_p_Pa,transfer_order,boundary_residual\n";
  for (std::size_t i = 0; i < e.modes(); ++i) {
    const auto m = kernels::transfer::stored_multipole(e.transfer, i);
    out += fmt::format("{},{:.9g},{:.9e},{},{:.2e}\n", i, e.frequencies_hz[i], std::abs(m.pressure(x)), m.order,
                       e.transfer.boundary_residual[i]);
  }
  return out;
}

}  // namespace clatter::jobs
