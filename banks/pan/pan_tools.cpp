#include "banks/pan/pan_tools.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>

#include "core/errors.hpp"
#include "io/h5.hpp"
#include "io/pan_bank.hpp"
#include "kernels/pan/directions.hpp"
#include "kernels/pan/field.hpp"

namespace clatter::jobs {

namespace {

// io's checks and the kernels' replay of every direction set (kernels/pan/field.hpp).
model::PanBank read_checked(const std::string& path) {
  model::PanBank bank = io::read_pan_bank(path);
  try {
    kernels::pan::check_direction_sets(bank);
  } catch (const std::invalid_argument& e) {
    throw InputError(path + ": " + e.what());
  }
  return bank;
}

}  // namespace

std::string pan_bank_info(const std::string& path) {
  const model::PanBank bank = read_checked(path);
  const auto& h = bank.header;
  auto file = io::File::open(path);
  auto prov = [&](const char* key) { return io::read_string_attribute(file, "/provenance", key); };
  auto run = [&](const char* key) { return io::read_string_attribute(file, "/provenance/run", key); };
  std::size_t kept = 0, directions = 0, fields = 0, fewest = SIZE_MAX, most = 0;
  for (const auto& p : bank.proxies)
    for (const auto& f : p.fields) {
      if (!f.solved()) continue;
      for (const auto& d : f.terms) kept += d.index.size();
      ++fields;
      directions += f.terms.size();
      fewest = std::min(fewest, f.terms.size());
      most = std::max(most, f.terms.size());
    }
  const double file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  const double raw_mb = static_cast<double>(directions) * static_cast<double>(h.values()) * h.length * 4 / 1e6;
  std::string out = fmt::format("{}: PAN bank (format {} v{})\n", path, io::kPanBankFormat, io::kPanBankFormatVersion);
  out += fmt::format("  proxies:     {} ellipsoids, A = {} m, fields 1-6 (translation x y z, rotation x y z)\n",
                     bank.proxies.size(), h.a_m);
  std::string list;
  for (const auto& p : bank.proxies) list += fmt::format(" ({:.4g}, {:.4g})", p.b_m, p.c_m);
  out += "  (B, C) [m]: " + list + "\n";
  out += fmt::format("  medium:      c = {} m/s, rho = {} kg/m^3; pulse h = {} s; t = 0 at the centre of psi\n", h.c_m_s,
                     h.rho_kg_m3, h.h_s);
  out += fmt::format("  sampling:    {:.6g} Hz, wavelet length {} (Daubechies 10)\n", 1.0 / h.dt_s, h.length);
  std::string radii;
  for (double r : h.radii_m) radii += fmt::format(" {:.4g}", r);
  out += fmt::format("  directions:  per field {} to {} ({:.1f} on average over {} fields): the octant cut in {}, split "
                     "up to {} times (lattice {})\n", fields ? fewest : 0, most,
                     fields ? static_cast<double>(directions) / static_cast<double>(fields) : 0.0, fields, h.divisions,
                     h.max_levels, h.lattice());
  out += fmt::format("  fit:         {} radii [m]:{} and the far field per direction; epsilon = {}\n", h.radii_m.size(),
                     radii, h.epsilon);
  out += fmt::format("  size:        {:.3f} MB on disk, {} coefficients kept ({:.2f} % of {:.1f} MB as raw float32 series)\n",
                     file_mb, kept, 100.0 * file_mb / raw_mb, raw_mb);
  out += fmt::format("  provenance:  clatter {} (git {}), {} ranks, created {}\n", prov("clatter_version"),
                     prov("git_revision"), io::read_attribute<std::int32_t>(file, "/provenance/run", "n_ranks"),
                     run("created_utc"));
  out += "  command:     " + run("command") + "\n";
  const auto& sw = bank.sweep;
  out += fmt::format("  sweep:       {} of {} tasks (proxy x field) in the bank, {} failed, {} missing\n",
                     sw.tasks_total - sw.failed.size() - sw.missing.size(), sw.tasks_total, sw.failed.size(),
                     sw.missing.size());
  for (const auto& f : sw.failed) out += "    failed:  " + f + "\n";
  for (const auto& m : sw.missing) out += "    missing: " + m + "\n";
  return out;
}

std::string probe_csv(const ProbeRequest& r) {
  const model::PanBank bank = read_checked(r.bank_path);
  const auto& h = bank.header;
  const model::PanProxy* proxy = nullptr;
  for (const auto& p : bank.proxies)
    if (std::abs(p.b_m - r.proxy_bc_m[0]) < 1e-9 && std::abs(p.c_m - r.proxy_bc_m[1]) < 1e-9) proxy = &p;
  if (!proxy) throw InputError(fmt::format("{}: no proxy (B, C) = ({}, {}) in the bank (see clatter-bank info)", r.bank_path,
                                           r.proxy_bc_m[0], r.proxy_bc_m[1]));
  if (r.field < 1 || r.field > 6) throw InputError(fmt::format("--field {}: the bank holds fields 1-6", r.field));
  if (!proxy->solved(r.field))
    throw InputError(fmt::format("{}: field {} was not solved for this proxy", r.bank_path, r.field));
  if (!(r.scale > 0)) throw InputError(fmt::format("--scale {}: must be > 0", r.scale));
  if (!(r.rate_hz >= 0)) throw InputError(fmt::format("--rate {}: must be >= 0 Hz (0: the bank's own rate)", r.rate_hz));
  const double dist = std::hypot(r.point_m[0], r.point_m[1], r.point_m[2]);
  if (!std::isfinite(dist))  // else NaN fails the bounding-sphere test below and is reported as inside
    throw InputError(fmt::format("--point {},{},{}: coordinates must be finite", r.point_m[0], r.point_m[1], r.point_m[2]));
  if (!(dist > h.a_m * r.scale))
    throw InputError(fmt::format("--point {},{},{}: |x| = {} m is inside the proxy's bounding sphere (radius A beta = {} m)",
                                 r.point_m[0], r.point_m[1], r.point_m[2], dist, h.a_m * r.scale));
  const auto s = kernels::pan::evaluate({&h, proxy, r.field}, r.point_m, r.scale, r.rate_hz, r.interpolation);
  std::string out = "t_s,p_Pa\n";
  for (std::size_t n = 0; n < s.p.size(); ++n)
    out += fmt::format("{:.9g},{:.9g}\n", s.t0_s + static_cast<double>(n) * s.dt_s, s.p[n]);
  return out;
}

}  // namespace clatter::jobs
