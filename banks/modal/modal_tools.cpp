#include "banks/modal/modal_tools.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "core/errors.hpp"
#include "io/h5.hpp"
#include "io/modal_bank.hpp"
#include "banks/modal/modal_spec.hpp"
#include "kernels/transfer/multipole.hpp"

namespace clatter::jobs {

std::string group_sizes(std::span<const std::int32_t> group_of_mode) {
  std::map<std::int32_t, int> size_of_group;
  for (std::int32_t g : group_of_mode) ++size_of_group[g];
  std::map<int, int> count_of_size;
  for (const auto& [group, size] : size_of_group) ++count_of_size[size];
  std::string out;
  for (const auto& [size, count] : count_of_size) out += fmt::format("{}{}x{}", out.empty() ? "" : ", ", size, count);
  return out;
}

std::string band_guarantee(const model::ModalEntry& e, const std::string& f_max_name) {
  const auto& b = e.band;
  return fmt::format("complete for every mode with exact frequency <= {}{:.2f} Hz given the mesh error <= {:.2e} "
                     "at f_max (every discrete mode to {:.2f} Hz stored, with the rest of its cluster)",
                     f_max_name, b.f_max_hz, b.mesh_error, b.keep_to_hz);
}

std::string symmetry_text(const model::ModalSymmetry& s) {
  if (s.kind == "spheroid") return fmt::format("spheroid about {}: doublets |m| >= 1, singles m = 0", "xyz"[s.axis]);
  if (s.kind == "sphere") return "sphere: 2n + 1 of degree n";
  return "none: every mode single";
}

std::string entry_table(const model::ModalEntry& e, std::size_t index) {
  return fmt::format("entry {}: axes ({:.6f}, {:.6f}, {:.6f}) m, {} modes; multiplets by symmetry: {}\n", index,
                     e.axes_m[0], e.axes_m[1], e.axes_m[2], e.modes(), symmetry_text(e.symmetry)) +
         modes_csv(e);
}

std::string modes_csv(const model::ModalEntry& e) {
  std::string out = "mode,frequency_hz,damping_ratio,cluster,cluster_size,multiplet,multiplet_size,symmetry_order,"
                    "relative_residual,transfer_order,boundary_residual,normal_attempts,sources\n";
  const auto& t = e.transfer;
  for (std::size_t i = 0; i < e.modes(); ++i) {
    const auto cluster_size = std::count(e.cluster.begin(), e.cluster.end(), e.cluster[i]);
    const auto multiplet_size = std::count(e.multiplet.begin(), e.multiplet.end(), e.multiplet[i]);
    out += fmt::format("{},{:.9g},{:.4g},{},{},{},{},{},{:.2e},{},{:.2e},{},{}\n", i, e.frequencies_hz[i],
                       e.damping_ratios[i], e.cluster[i], cluster_size, e.multiplet[i], multiplet_size,
                       e.symmetry_order[i], e.relative_residuals[i], t.order[i], t.boundary_residual[i], t.attempts[i],
                       t.sources[i]);
  }
  return out;
}

std::string modal_probe_csv(const std::string& path, std::size_t entry, const std::array<double, 3>& point_m,
                            double scale) {
  const model::ModalBank bank = io::read_modal_bank(path);
  if (entry >= bank.entries.size())
    throw InputError(fmt::format("--entry {}: {} holds entries 0-{}", entry, path, bank.entries.size() - 1));
  if (!(scale > 0)) throw InputError(fmt::format("--scale {}: must be positive", scale));
  const Eigen::Vector3d x(point_m[0], point_m[1], point_m[2]);
  const auto& e = bank.entries[entry];
  // The expansion holds outside the sphere around its sources; the bank promises r >= 2c.
  if (x.norm() < 2 * scale * e.axes_m[2])
    throw InputError(fmt::format("--point {},{},{}: {:.4g} m from the centre; the transfer holds from 2c = {:.4g} m",
                                 point_m[0], point_m[1], point_m[2], x.norm(), 2 * scale * e.axes_m[2]));
  std::string out = "mode,frequency_hz,abs_p_Pa,transfer_order,boundary_residual\n";
  for (std::size_t i = 0; i < e.modes(); ++i) {
    const auto m = kernels::transfer::scaled(kernels::transfer::stored_multipole(e.transfer, i), scale);
    out += fmt::format("{},{:.9g},{:.9e},{},{:.2e}\n", i, e.frequencies_hz[i] / scale, std::abs(m.pressure(x)),
                       m.order, e.transfer.boundary_residual[i]);
  }
  return out;
}

std::string modal_bank_info(const std::string& path, std::optional<std::size_t> entry) {
  const model::ModalBank bank = io::read_modal_bank(path);
  if (entry) {
    if (*entry >= bank.entries.size())
      throw InputError(fmt::format("--entry {}: {} holds entries 0-{}", *entry, path, bank.entries.size() - 1));
    return entry_table(bank.entries[*entry], *entry);
  }
  const auto& h = bank.header;
  const auto& m = h.material;
  const double file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::string out = fmt::format("{}: modal bank (format {} v{}), {} ellipsoids, {:.3f} MB on disk\n", path,
                                io::kModalBankFormat, io::kModalBankFormatVersion, bank.entries.size(), file_mb);
  out += fmt::format("  material:   {}: rho = {} kg/m^3, E = {:.4g} Pa, nu = {}, c_s = {:.1f} m/s; Rayleigh alpha = {} "
                     "1/s, beta = {} s\n", m.name, m.rho_kg_m3, m.youngs_pa, m.poisson, m.shear_speed_m_s(),
                     m.damping.value_or(model::RayleighDamping{}).alpha_1_s, m.damping.value_or(model::RayleighDamping{}).beta_s);
  out += fmt::format("  settings:   {}, and on by the mesh's error margin; h = shear wavelength at f_max / {}; "
                     "patch: min a/c {}, cigar b/c {}; clusters split by > {}; tolerance {}, residuals <= {}; {} rank(s) per entry\n", band_text(h),
                     h.elements_per_wavelength, h.min_ratio, h.cigar_ratio, h.solve.cluster_gap, h.solve.tolerance,
                     h.solve.residual_limit, h.ranks_per_task);
  const auto& tr = h.transfer;
  out += fmt::format("  transfer:   {}; air c = {} m/s, rho = {} kg/m^3; {} fit points per source (per angle), {} sources per wavelength, "
                     "residual target {}, tail {}\n", tr.method, tr.sound_speed_m_s, tr.air_density_kg_m3,
                     tr.points_per_source, tr.sources_per_wavelength, tr.residual_target, tr.tail_tolerance);
  out += fmt::format("  band:       entry k: modes [f_1, k f_1]; L_all: the longest piece of the entry's shape (in {}) that gets "
                     "every mode to {:g} Hz by equi-frequency scaling (f_0 = f_1 2c / L, complete while k f_0 >= {:g} Hz)\n",
                     m.name, h.band.top_hz, h.band.top_hz);
  out += "  entry  a        b        c        k      L_all [m]  modes  f_1 [Hz]   last [Hz]   dofs     max res   min dihedral  time [s]  "
         "transfer: max order, max boundary res (normal fraction > 0.3), s  "
         + fmt::format("clusters (frequencies within {:g} %; size x count)\n", 100 * h.solve.cluster_gap);
  for (std::size_t i = 0; i < bank.entries.size(); ++i) {
    const auto& e = bank.entries[i];
    const double worst = e.modes() ? *std::max_element(e.relative_residuals.begin(), e.relative_residuals.end()) : 0;
    const auto& t = e.transfer;
    const int order = e.modes() ? *std::max_element(t.order.begin(), t.order.end()) : 0;
    double boundary = 0;  // over the modes that push the air (a torsional mode's residual is its noise's)
    for (std::size_t k = 0; k < e.modes(); ++k)
      if (t.normal_fraction[k] > model::kNormalFractionPromised) boundary = std::max(boundary, t.boundary_residual[k]);
    // Equi-frequency scaling: a piece of this shape and longest dimension L has f_0 = f_1 2c / L,
    // so it gets every mode to the top while k f_0 >= top, L <= 2 c k f_1 / top.
    const double f1 = e.modes() ? e.frequencies_hz.front() : 0.0, k = f1 > 0 ? e.band.f_max_hz / f1 : 0.0;
    const double complete_m = 2 * e.axes_m[2] * k * f1 / h.band.top_hz;
    out += fmt::format("  {:<5}  {:.5f}  {:.5f}  {:.5f}  {:<5.2f}  {:<9.3f}  {:<5}  {:<9.2f}  {:<10.2f}  {:<7}  {:.1e}   {:<12.1f}  {:<8.1f}  "
                       "{:<3} {:.1e} {:<7.1f}                                        {}\n", i, e.axes_m[0], e.axes_m[1], e.axes_m[2], k, complete_m,
                       e.modes(), f1, e.modes() ? e.frequencies_hz.back() : 0.0,
                       e.mesh.dofs, worst, e.mesh.min_dihedral_deg, e.cost.total_s, order, boundary, e.cost.transfer_s,
                       group_sizes(e.cluster));
    out += fmt::format("         multiplets (degenerate by symmetry; size x count): {} [{}; |order - integer| <= {:.2f}, "
                       "{} incomplete]\n", group_sizes(e.multiplet), symmetry_text(e.symmetry), e.symmetry.order_defect,
                       e.symmetry.incomplete);
    out += "         band: " + band_guarantee(e, fmt::format("{:.3g} f_1 = ", k)) +
           fmt::format("; a piece scaled by equi-frequency scaling gets every mode to {:.3g} f_0: complete to {:g} Hz for "
                       "pieces of this shape with f_0 >= {:.0f} Hz, up to {:.3f} m long in {}\n", k, h.band.top_hz,
                       k > 0 ? h.band.top_hz / k : 0.0, complete_m, m.name);
  }
  const auto& sw = bank.sweep;
  out += fmt::format("  sweep:      {} of {} entries in the bank, {} failed, {} missing\n", sw.tasks_done(),
                     sw.tasks_total, sw.failed.size(), sw.missing.size());
  for (const auto& f : sw.failed) out += "    failed:  " + f + "\n";
  for (const auto& x : sw.missing) out += "    missing: " + x + "\n";
  return out;
}

}  // namespace clatter::jobs
