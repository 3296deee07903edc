#include "jobs/bank_tools.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>

#include "core/errors.hpp"
#include "io/content_hash.hpp"
#include "io/h5.hpp"
#include "io/pan_bank.hpp"
#include "jobs/command.hpp"
#include "jobs/ground_tools.hpp"
#include "jobs/modal_tools.hpp"
#include "kernels/pan/field.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {

std::string bank_info(const std::string& path) {
  const model::PanBank bank = io::read_pan_bank(path);
  const auto& h = bank.header;
  auto file = io::File::open(path);
  auto prov = [&](const char* key) { return io::read_string_attribute(file, "/provenance", key); };
  auto run = [&](const char* key) { return io::read_string_attribute(file, "/provenance/run", key); };
  std::size_t kept = 0;
  for (const auto& p : bank.proxies)
    for (const auto& f : p.fields)
      for (const auto& d : f) kept += d.index.size();
  const double file_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  const double raw_mb = static_cast<double>(bank.proxies.size()) * 6 * static_cast<double>(h.directions.size()) *
                        static_cast<double>(h.terms) * h.length * 4 / 1e6;
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
  out += fmt::format("  fit:         {} directions x {} radii [m]:{}; N = {} terms; epsilon = {}\n", h.directions.size(),
                     h.radii_m.size(), radii, h.terms, h.epsilon);
  out += fmt::format("  size:        {:.3f} MB on disk, {} coefficients kept ({:.2f} % of {:.1f} MB as raw float32 q_k)\n",
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
  const model::PanBank bank = io::read_pan_bank(r.bank_path);
  const auto& h = bank.header;
  const model::PanProxy* proxy = nullptr;
  for (const auto& p : bank.proxies)
    if (std::abs(p.b_m - r.proxy_bc_m[0]) < 1e-9 && std::abs(p.c_m - r.proxy_bc_m[1]) < 1e-9) proxy = &p;
  if (!proxy) throw InputError(fmt::format("{}: no proxy (B, C) = ({}, {}) in the bank (see clatter-bank info)", r.bank_path,
                                           r.proxy_bc_m[0], r.proxy_bc_m[1]));
  if (kernels::pan::divisions_of(h.directions.size()) % 2 != 0 || h.directions.size() < 3)
    throw InputError(fmt::format("{}: /bank/directions holds {} directions: not an octant triangulation with an even "
                                 "number of divisions", r.bank_path, h.directions.size()));
  if (r.field < 1 || r.field > 6) throw InputError(fmt::format("--field {}: the bank holds fields 1-6", r.field));
  if (proxy->field(r.field).size() != h.directions.size())
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

namespace {

// Serial work that every rank does (so all agree on errors) and rank 0 prints.
int print_on_root(const JobContext& context, const std::function<std::string()>& make_text) {
  std::string text;
  mpi::agree(context.world, [&] { text = make_text(); });
  if (context.is_root) std::fputs(text.c_str(), stdout);
  return kExitOk;
}

}  // namespace

Command add_checksum_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("checksum", "print a content hash of a Clatter HDF5 file that leaves out "
                                                "/provenance/run (who ran it, when, on how many ranks)");
  auto path = std::make_shared<std::string>();
  app->add_option("file", *path, "HDF5 file")->required();
  return {app, [path](const JobContext& context) -> int {
            return print_on_root(context, [&] {
              auto file = io::File::open(*path);
              return io::hash_hex(io::content_hash(file, {{"/provenance/run"}, {}})) + "  " + *path + "\n";
            });
          }};
}

Command add_info_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("info", "describe a bank: a PAN bank's proxies, fields, epsilon, size, provenance; "
                                            "a modal bank's entries, modes and multiplicities; a ground bank's "
                                            "materials and grid");
  auto path = std::make_shared<std::string>();
  auto entry = std::make_shared<std::optional<std::size_t>>();
  app->add_option("bank", *path, "PAN, modal or ground bank file")->required();
  app->add_option("--entry", *entry, "modal bank: list this entry's modes (index, frequency, damping, multiplet, "
                                     "multiplicity, residual) as CSV");
  return {app, [path, entry](const JobContext& context) -> int {
            return print_on_root(context, [&] {
              if (is_modal_bank(*path)) return modal_bank_info(*path, *entry);
              if (entry->has_value()) throw InputError("--entry: only for a modal bank; " + *path + " is not one");
              if (is_ground_bank(*path)) return ground_bank_info(*path);
              return bank_info(*path);
            });
          }};
}

Command add_probe_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("probe", "print p_i(x, t) of one proxy from a PAN bank as t_s,p_Pa CSV, or "
                                             "|p_i(x)| of every mode of one modal-bank entry");
  auto request = std::make_shared<ProbeRequest>();
  auto entry = std::make_shared<std::optional<std::size_t>>();
  ProbeRequest& r = *request;
  app->add_option("bank", r.bank_path, "PAN or modal bank file")->required();
  app->add_option("--proxy", r.proxy_bc_m, "PAN: proxy semi-axes B,C [m]")->delimiter(',');
  app->add_option("--field", r.field, "PAN: rigid-body field 1-6");
  app->add_option("--entry", *entry, "modal: the entry whose modes to evaluate");
  app->add_option("--point", r.point_m, "listener x,y,z [m], proxy centred on the origin")->delimiter(',')->required();
  app->add_option("--rate", r.rate_hz, "output sample rate [Hz]: reconstruct within 2x of it (Algorithm 1); "
                                       "0: the bank's rate")
      ->capture_default_str();
  app->add_option("--scale", r.scale, "beta: the proxy scaled by beta (eq. 10)")->capture_default_str();
  app->add_option("--interpolation", r.interpolation, "between directions: quadratic (default) or linear (the paper's)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, kernels::pan::Interpolation>{
          {"linear", kernels::pan::Interpolation::linear}, {"quadratic", kernels::pan::Interpolation::quadratic}}));
  return {app, [request, entry, app](const JobContext& context) -> int {
            return print_on_root(context, [&] {
              const ProbeRequest& q = *request;
              if (is_modal_bank(q.bank_path)) {
                if (!entry->has_value()) throw InputError("probe " + q.bank_path + ": a modal bank needs --entry N");
                return modal_probe_csv(q.bank_path, **entry, q.point_m, q.scale);
              }
              if (entry->has_value()) throw InputError("--entry: only for a modal bank; " + q.bank_path + " is not one");
              if (app->count("--proxy") == 0 || app->count("--field") == 0)
                throw InputError("probe " + q.bank_path + ": a PAN bank needs --proxy B,C and --field N");
              return probe_csv(q);
            });
          }};
}

}  // namespace clatter::jobs
