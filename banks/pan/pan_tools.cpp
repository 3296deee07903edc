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
#include <vector>

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

std::string entry_label(const model::PanProxy& entry) {
  return entry.is_mesh() ? fmt::format("mesh {}", entry.mesh.key.substr(0, 12)) : fmt::format("({:.4g}, {:.4g})", entry.b_m, entry.c_m);
}

std::string held_out_summary(const model::PanBank& bank, bool table) {
  struct Row {
    std::size_t proxy;
    int field;
    double share, median, worst, floored;
    std::size_t above, points;
  };
  std::vector<Row> rows;
  std::size_t checked = 0;
  for (std::size_t p = 0; p < bank.proxies.size(); ++p) {
    const auto& proxy = bank.proxies[p];
    std::array<double, 6> energy{};
    for (std::size_t f = 0; f < 6; ++f) {
      for (double l2 : proxy.held_out[f].raw_l2) energy[f] += l2 * l2;
      if (f >= 3) energy[f] /= bank.header.a_m * bank.header.a_m;
    }
    const double strongest = *std::max_element(energy.begin(), energy.end());
    for (std::size_t f = 0; f < 6; ++f) {
      const auto& c = proxy.held_out[f];
      if (c.error.empty()) continue;
      ++checked;
      std::map<long, double> radius_peak;  // by radius in micrometres: the field's largest raw L2 there
      auto radius_key = [](const std::array<double, 3>& x) { return std::lround(1e6 * std::hypot(x[0], x[1], x[2])); };
      for (std::size_t l = 0; l < c.error.size(); ++l)
        radius_peak[radius_key(c.points_m[l])] = std::max(radius_peak[radius_key(c.points_m[l])], c.raw_l2[l]);
      Row r{p, static_cast<int>(f + 1), strongest > 0 ? energy[f] / strongest : 0.0, 0, 0, 0, 0, c.error.size()};
      std::vector<double> sorted = c.error;
      std::sort(sorted.begin(), sorted.end());
      r.median = sorted[sorted.size() / 2];
      r.worst = sorted.back();
      for (std::size_t l = 0; l < c.error.size(); ++l) {
        r.above += c.error[l] > 0.05;
        r.floored = std::max(r.floored, c.error[l] * c.raw_l2[l] / std::max(c.raw_l2[l], 0.1 * radius_peak[radius_key(c.points_m[l])]));
      }
      rows.push_back(r);
    }
  }
  if (checked == 0) return "no held-out checks (check.held_out_directions = 0, or a bank merged before them)";
  auto name = [&](const Row& r) {
    return fmt::format("{} field {}", entry_label(bank.proxies[r.proxy]), r.field);
  };
  std::string out;
  if (table) {
    out += fmt::format("  {:<26} {:>7} {:>8} {:>8} {:>9} {:>9}\n", "entry (B, C [m]), field", "energy", "median",
                       "worst", "floored", "> 5 %");
    for (const auto& r : rows) {
      if (r.share < kExcludedEnergy)
        out += fmt::format("  {:<26} {:>7.4f}   not radiated: excluded\n", name(r), r.share);
      else
        out += fmt::format("  {:<26} {:>7.4f} {:>7.2f}% {:>7.2f}% {:>8.2f}% {:>5}/{}\n", name(r), r.share, 100 * r.median,
                           100 * r.worst, 100 * r.floored, r.above, r.points);
    }
  }
  const Row* worst = nullptr;
  const Row* worst_floored = nullptr;
  std::size_t excluded = 0;
  for (const auto& r : rows) {
    if (r.share < kExcludedEnergy) {
      ++excluded;
      continue;
    }
    if (!worst || r.worst > worst->worst) worst = &r;
    if (!worst_floored || r.floored > worst_floored->floored) worst_floored = &r;
  }
  const std::string indent = table ? "  " : "";
  if (!worst) return out + indent + fmt::format("held out: {} fields checked, none radiated", checked);
  out += indent + fmt::format("held out: worst {:.2f} % ({}), floored {:.2f} % ({}); {} of {} fields not radiated (below {:g} % "
                     "of their entry's strongest energy), excluded",
                     100 * worst->worst, name(*worst), 100 * worst_floored->floored, name(*worst_floored), excluded, checked,
                     100 * kExcludedEnergy);
  return out;
}

std::string pan_bank_info(const std::string& path) {
  const model::PanBank bank = read_checked(path);
  const auto& h = bank.header;
  auto file = io::File::open(path);
  auto prov = [&](const char* key) { return io::read_string_attribute(file, "/provenance", key); };
  auto run = [&](const char* key) { return io::read_string_attribute(file, "/provenance/run", key); };
  std::size_t kept = 0, directions = 0, fields = 0, fewest = SIZE_MAX, most = 0;
  for (const auto& p : bank.proxies)
    for (int o = 0; o < p.octants(); ++o)
    for (int field = 1; field <= 6; ++field) {
      const model::PanField& f = p.field(field, o);
      if (!f.solved()) continue;
      for (const auto& d : f.terms) kept += d.index.size();
      ++fields;
      directions += f.terms.size();
      fewest = std::min(fewest, f.terms.size());
      most = std::max(most, f.terms.size());
    }
  const double file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  const double raw_mb = static_cast<double>(directions) * static_cast<double>(h.values()) * h.length * 4 / 1e6;
  std::string out = fmt::format("{}: PAN bank (format {} v{})\n", path, io::kPanBankFormat,
                                io::read_attribute<std::int32_t>(file, "/", "format_version"));
  const auto meshes = static_cast<std::size_t>(
      std::count_if(bank.proxies.begin(), bank.proxies.end(), [](const model::PanProxy& p) { return p.is_mesh(); }));
  out += fmt::format("  entries:     {} ellipsoids and {} meshes, A = {} m, fields 1-6 (translation x y z, rotation x y z)\n",
                     bank.proxies.size() - meshes, meshes, h.a_m);
  std::string list;
  for (const auto& p : bank.proxies)
    if (!p.is_mesh()) list += fmt::format(" ({:.4g}, {:.4g})", p.b_m, p.c_m);
  if (meshes < bank.proxies.size()) out += "  (B, C) [m]: " + list + "\n";
  for (const auto& p : bank.proxies)
    if (p.is_mesh())
      out += fmt::format("  mesh:        {}: scaled by {:.6g} to bounding radius A about its centre of mass ({:.6g}, "
                         "{:.6g}, {:.6g}) m (the mesh as given: --scale {:.6g}); {} support points; {}\n",
                         p.mesh.key, p.mesh.scale, p.mesh.centre_of_mass_m[0], p.mesh.centre_of_mass_m[1],
                         p.mesh.centre_of_mass_m[2], 1.0 / p.mesh.scale, p.mesh.support_points_m.size(),
                         p.octants() == 8 ? "eight octants of directions (full-domain solve)"
                                          : "mirror-symmetric: one octant of directions");
  out += fmt::format("  medium:      c = {} m/s, rho = {} kg/m^3; pulse h = {} s; t = 0 at the centre of psi\n", h.c_m_s,
                     h.rho_kg_m3, h.h_s);
  out += fmt::format("  sampling:    {:.6g} Hz, wavelet length {} (Daubechies 10)\n", 1.0 / h.dt_s, h.length);
  std::string radii;
  for (double r : h.radii_m) radii += fmt::format(" {:.4g}", r);
  out += fmt::format("  directions:  per field and octant {} to {} ({:.1f} on average over {} sets): the octant cut in {}, split "
                     "up to {} times (lattice {})\n", fields ? fewest : 0, most,
                     fields ? static_cast<double>(directions) / static_cast<double>(fields) : 0.0, fields, h.divisions,
                     h.max_levels, h.lattice());
  out += fmt::format("  fit:         {} radii [m]:{} and the far field per direction; epsilon = {}\n", h.radii_m.size(),
                     radii, h.epsilon);
  out += fmt::format("  size:        {:.3f} MB on disk, {} coefficients kept ({:.2f} % of {:.1f} MB as raw float32 series)\n",
                     file_mb, kept, 100.0 * file_mb / raw_mb, raw_mb);
  if (bank.proxies.size() > 1 && kept > 0) {
    // Each entry's share of the file, by its kept coefficients (the bulk of the file: a coefficient
    // is M + 1 quantized values): what a bank of other entries would weigh (docs/pan.md).
    out += "  per entry:   directions (all fields), coefficients as read, their share of the file\n";
    for (const auto& p : bank.proxies) {
      std::size_t n = 0, d = 0;
      for (int o = 0; o < p.octants(); ++o)
        for (int field = 1; field <= 6; ++field)
          for (const auto& t : p.field(field, o).terms) {
            n += t.index.size();
            ++d;
          }
      if (d == 0) continue;
      out += fmt::format("    {:<24} {:6} {:9}  {:.3f} MB\n", entry_label(p), d, n,
                         file_mb * static_cast<double>(n) / static_cast<double>(kept));
    }
  }
  out += fmt::format("  provenance:  clatter {} (git {}), {} ranks, created {}\n", prov("clatter_version"),
                     prov("git_revision"), io::read_attribute<std::int32_t>(file, "/provenance/run", "n_ranks"),
                     run("created_utc"));
  out += "  command:     " + run("command") + "\n";
  const auto& sw = bank.sweep;
  out += fmt::format("  sweep:       {} of {} tasks (entry x field) in the bank, {} failed, {} missing\n",
                     sw.tasks_total - sw.failed.size() - sw.missing.size(), sw.tasks_total, sw.failed.size(),
                     sw.missing.size());
  for (const auto& f : sw.failed) out += "    failed:  " + f + "\n";
  for (const auto& m : sw.missing) out += "    missing: " + m + "\n";
  std::size_t points = 0;
  for (const auto& p : bank.proxies)
    for (const auto& c : p.held_out) points = std::max(points, c.error.size());
  out += fmt::format("  held out:    {} points per field (directions x radii), each field as stored against its raw "
                     "solve there (relative L2; docs/pan.md, \"The held-out check\")\n", points);
  out += held_out_summary(bank, true) + "\n";
  return out;
}

std::string probe_csv(const ProbeRequest& r) {
  const model::PanBank bank = read_checked(r.bank_path);
  const auto& h = bank.header;
  const model::PanProxy* proxy = nullptr;
  for (const auto& p : bank.proxies) {
    if (!r.mesh_key.empty() ? p.is_mesh() && p.mesh.key.starts_with(r.mesh_key)
                            : !p.is_mesh() && std::abs(p.b_m - r.proxy_bc_m[0]) < 1e-9 && std::abs(p.c_m - r.proxy_bc_m[1]) < 1e-9) {
      if (proxy) throw InputError(fmt::format("{}: --mesh {} names more than one mesh entry: give more of its key", r.bank_path, r.mesh_key));
      proxy = &p;
    }
  }
  if (!proxy)
    throw InputError(!r.mesh_key.empty()
                         ? fmt::format("{}: no mesh entry with a key starting '{}' in the bank (see clatter-bank info)",
                                       r.bank_path, r.mesh_key)
                         : fmt::format("{}: no proxy (B, C) = ({}, {}) in the bank (see clatter-bank info)", r.bank_path,
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
