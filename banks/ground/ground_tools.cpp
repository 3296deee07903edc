#include "banks/ground/ground_tools.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

#include "io/ground_bank.hpp"
#include "kernels/ground/lamb.hpp"

namespace clatter::jobs {
namespace {

std::string degrees_text(const std::vector<double>& rad) {
  std::string out;
  for (double x : rad) out += fmt::format("{}{:.4g}", out.empty() ? "" : " ", x * 180 / std::numbers::pi);
  return out;
}

std::string material_line(const model::GroundMaterial& m, double c0_m_s) {
  std::size_t samples = 0;
  double t_lo = std::numeric_limits<double>::infinity(), t_hi = -t_lo;
  for (const auto& s : m.series) {
    samples += s.pi.size();
    t_lo = std::min(t_lo, s.t_hat_start);
    t_hi = std::max(t_hi, s.t_hat_start + static_cast<double>(s.pi.size() - 1) * s.dt_hat);
  }
  return fmt::format("  {:<9} E = {:.3g} Pa, nu = {}, rho = {} kg/m^3; c_s = {:.1f}, c_p = {:.1f} m/s, M = c_s/c0 = {:.3f}\n"
                     "            elevations [deg]: {}; {} etas in [{:.3g}, {:.3g}]; {} samples of Pi, "
                     "t_hat in [{:.3f}, {:.3f}]\n",
                     m.name, m.youngs_pa, m.poisson, m.rho_kg_m3, m.shear_speed_m_s(), m.pressure_speed_m_s(),
                     m.shear_speed_m_s() / c0_m_s, degrees_text(m.elevation_rad), m.eta.size(), m.eta.front(),
                     m.eta.back(), samples, t_lo, t_hi);
}

}  // namespace

std::string ground_bank_info(const std::string& path) {
  const model::GroundBank bank = io::read_ground_bank(path);
  auto file = io::File::open(path);
  auto prov = [&](const char* key) { return io::read_string_attribute(file, "/provenance", key); };
  auto run = [&](const char* key) { return io::read_string_attribute(file, "/provenance/run", key); };
  const double file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::string out = fmt::format("{}: ground bank (format {} v{}), {} materials, {:.3f} MB on disk\n", path,
                                io::kGroundBankFormat, io::kGroundBankFormatVersion, bank.materials.size(), file_mb);
  out += fmt::format("  air:        c0 = {} m/s, rho0 = {} kg/m^3\n", bank.c0_m_s, bank.rho0_kg_m3);
  for (const auto& m : bank.materials) out += material_line(m, bank.c0_m_s);
  out += fmt::format("  provenance: clatter {} (git {}), {} ranks, created {}\n", prov("clatter_version"),
                     prov("git_revision"), io::read_attribute<std::int32_t>(file, "/provenance/run", "n_ranks"),
                     run("created_utc"));
  out += "  command:    " + run("command") + "\n";
  const auto& sw = bank.sweep;
  out += fmt::format("  sweep:      {} of {} tasks (material x elevation) in the bank, {} failed, {} missing\n",
                     sw.tasks_done(), sw.tasks_total, sw.failed.size(), sw.missing.size());
  for (const auto& f : sw.failed) out += "    failed:  " + f + "\n";
  for (const auto& x : sw.missing) out += "    missing: " + x + "\n";
  return out;
}

}  // namespace clatter::jobs
