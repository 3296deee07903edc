#include "io/ground_bank.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "core/errors.hpp"
#include "io/provenance.hpp"
#include "io/sweep_files.hpp"

namespace clatter::io {
namespace {

using model::GroundMaterial;
using model::GroundSeries;

// The ragged series of one grid (a material's, or a task's row) under group `g`: index arrays
// [n] and the samples concatenated in `pi`, in series order.
void write_series(File& f, const std::string& g, const std::vector<GroundSeries>& series) {
  const std::size_t n = series.size();
  std::vector<std::int64_t> offset(n), length(n);
  std::vector<double> start(n), dt(n), pi, tail;
  for (std::size_t k = 0; k < n; ++k) {
    if (series[k].tail.size() != model::kGroundTailTerms)
      throw std::invalid_argument(fmt::format("ground bank: series {} has {} tail coefficients, not {}", k, series[k].tail.size(),
                                              model::kGroundTailTerms));
    tail.insert(tail.end(), series[k].tail.begin(), series[k].tail.end());
    offset[k] = static_cast<std::int64_t>(pi.size());
    length[k] = static_cast<std::int64_t>(series[k].pi.size());
    start[k] = series[k].t_hat_start;
    dt[k] = series[k].dt_hat;
    pi.insert(pi.end(), series[k].pi.begin(), series[k].pi.end());
  }
  write_dataset<std::int64_t>(f, g + "/series_offset", offset, {n}, "1", true);
  write_dataset<std::int64_t>(f, g + "/series_length", length, {n}, "1", true);
  write_dataset<double>(f, g + "/t_hat_start", start, {n}, "1", true);
  write_dataset<double>(f, g + "/dt_hat", dt, {n}, "1", true);
  write_dataset<double>(f, g + "/pi", pi, {pi.size()}, "1", true);
  write_dataset<double>(f, g + "/tail", tail, {n, model::kGroundTailTerms}, "1", true);
}

// The n series under `g`, every one checked: contiguous offsets covering `pi` exactly, at least two
// samples (a pressure needs a difference), positive dt_hat, finite values and tail coefficients.
std::vector<GroundSeries> read_series(const File& f, const std::string& g, std::size_t n) {
  const auto count = static_cast<long long>(n);
  const auto offset = read_dataset<std::int64_t>(f, g + "/series_offset", {count}, "1");
  const auto length = read_dataset<std::int64_t>(f, g + "/series_length", {count}, "1");
  const auto start = read_dataset<double>(f, g + "/t_hat_start", {count}, "1");
  const auto dt = read_dataset<double>(f, g + "/dt_hat", {count}, "1");
  const auto pi = read_dataset<double>(f, g + "/pi", {-1}, "1");
  const auto tail = read_dataset<double>(f, g + "/tail", {count, static_cast<long long>(model::kGroundTailTerms)}, "1");
  auto bad = [&](const std::string& name, std::size_t k, const std::string& what) {
    return InputError(fmt::format("{}: dataset '{}/{}': [{}] {}", f.path(), g, name, k, what));
  };
  std::vector<GroundSeries> out(n);
  std::int64_t next = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (offset[k] != next)
      throw bad("series_offset", k, fmt::format("= {}: the series are not contiguous (expected {})", offset[k], next));
    if (length[k] < 2) throw bad("series_length", k, fmt::format("= {}: a series needs at least 2 samples", length[k]));
    next += length[k];
    if (next > static_cast<std::int64_t>(pi.size()))
      throw bad("series_length", k,
                fmt::format("= {}: ends at {}, past the {} samples of '{}/pi'", length[k], next, pi.size(), g));
    if (!std::isfinite(start[k])) throw bad("t_hat_start", k, fmt::format("= {}: must be finite", start[k]));
    if (!(dt[k] > 0) || !std::isfinite(dt[k])) throw bad("dt_hat", k, fmt::format("= {}: must be > 0 and finite", dt[k]));
    out[k].t_hat_start = start[k];
    out[k].dt_hat = dt[k];
    out[k].pi.assign(pi.begin() + offset[k], pi.begin() + next);
    const auto tail_k = tail.begin() + static_cast<std::ptrdiff_t>(k * model::kGroundTailTerms);
    out[k].tail.assign(tail_k, tail_k + static_cast<std::ptrdiff_t>(model::kGroundTailTerms));
    for (std::size_t j = 0; j < model::kGroundTailTerms; ++j)
      if (!std::isfinite(out[k].tail[j])) throw bad("tail", k, fmt::format("[{}] = {}: must be finite", j, out[k].tail[j]));
  }
  if (next != static_cast<std::int64_t>(pi.size()))
    throw InputError(fmt::format("{}: dataset '{}/pi': {} samples, the series hold {}", f.path(), g, pi.size(), next));
  for (std::size_t i = 0; i < pi.size(); ++i)
    if (!std::isfinite(pi[i])) throw bad("pi", i, fmt::format("= {}: must be finite", pi[i]));
  return out;
}

// A strictly ascending grid of finite values in (lo, hi] (`rule` says so in the message).
std::vector<double> read_grid(const File& f, const std::string& name, const char* units, double lo, double hi,
                              const char* rule) {
  auto grid = read_dataset<double>(f, name, {-1}, units);
  if (grid.empty()) throw InputError(fmt::format("{}: dataset '{}' is empty", f.path(), name));
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (!(grid[i] > lo && grid[i] <= hi) || !std::isfinite(grid[i]))
      throw InputError(fmt::format("{}: dataset '{}': [{}] = {}: must be {}", f.path(), name, i, grid[i], rule));
    if (i > 0 && !(grid[i] > grid[i - 1]))
      throw InputError(fmt::format("{}: dataset '{}': [{}] = {} is not above [{}] = {}: not ascending", f.path(), name, i,
                                   grid[i], i - 1, grid[i - 1]));
  }
  return grid;
}

void write_material(File& f, const std::string& g, const GroundMaterial& m, std::size_t index) {
  const std::size_t n = m.elevation_rad.size() * m.eta.size();
  if (m.series.size() != n)
    throw std::invalid_argument(
        fmt::format("ground bank: material '{}': {} series for {} grid points", m.name, m.series.size(), n));
  create_group(f, g);
  write_attribute<std::int32_t>(f, g, "index", static_cast<std::int32_t>(index));
  write_attribute<double>(f, g, "youngs_pa", m.youngs_pa);
  write_attribute<double>(f, g, "poisson", m.poisson);
  write_attribute<double>(f, g, "rho_kg_m3", m.rho_kg_m3);
  write_attribute(f, g, "source", m.source);
  write_attribute<double>(f, g, "shear_speed_m_s", m.shear_speed_m_s());
  write_attribute<double>(f, g, "pressure_speed_m_s", m.pressure_speed_m_s());
  write_dataset<double>(f, g + "/elevation_rad", m.elevation_rad, {m.elevation_rad.size()}, "rad", true);
  write_dataset<double>(f, g + "/eta", m.eta, {m.eta.size()}, "1", true);
  write_series(f, g, m.series);
}

// A double attribute, checked finite and in the open interval (lo, hi).
double read_positive(const File& f, const std::string& g, const char* name, double lo = 0,
                     double hi = std::numeric_limits<double>::infinity()) {
  const double x = read_attribute<double>(f, g, name);
  if (!(x > lo && x < hi) || !std::isfinite(x))
    throw InputError(fmt::format("{}: attribute '{}' of '{}' = {}: must be in ({}, {})", f.path(), name, g, x, lo, hi));
  return x;
}

GroundMaterial read_material(const File& f, const std::string& g, const std::string& name) {
  GroundMaterial m;
  m.name = name;
  m.youngs_pa = read_positive(f, g, "youngs_pa");
  m.poisson = read_positive(f, g, "poisson", 0, 0.5);
  m.rho_kg_m3 = read_positive(f, g, "rho_kg_m3");
  m.source = read_string_attribute(f, g, "source");
  // The derived speeds are what an h5py reader sees: they must be the moduli's.
  const std::pair<const char*, double> derived[] = {{"shear_speed_m_s", m.shear_speed_m_s()},
                                                    {"pressure_speed_m_s", m.pressure_speed_m_s()}};
  for (const auto& [attr, want] : derived) {
    const double found = read_attribute<double>(f, g, attr);
    if (!(std::abs(found - want) <= 1e-9 * want))
      throw InputError(fmt::format("{}: attribute '{}' of '{}' = {}: the moduli give {}", f.path(), attr, g, found, want));
  }
  m.elevation_rad = read_grid(f, g + "/elevation_rad", "rad", 0, std::numbers::pi / 2, "in (0, pi/2]");
  m.eta = read_grid(f, g + "/eta", "1", 0, std::numeric_limits<double>::infinity(), "finite and > 0");
  m.series = read_series(f, g, m.elevation_rad.size() * m.eta.size());
  return m;
}

}  // namespace

void write_ground_bank(const std::string& path, const model::GroundBank& bank, const std::string& command,
                       const std::string& config_toml, int n_ranks) {
  auto file = File::create(path);
  write_header(file, kGroundBankFormat, kGroundBankFormatVersion);
  create_group(file, "/air");
  write_attribute<double>(file, "/air", "c0_m_s", bank.c0_m_s);
  write_attribute<double>(file, "/air", "rho0_kg_m3", bank.rho0_kg_m3);
  create_group(file, "/materials");
  for (std::size_t i = 0; i < bank.materials.size(); ++i) {
    const std::string& name = bank.materials[i].name;
    if (name.empty() || name.find_first_of("/.") != std::string::npos)
      throw std::invalid_argument("ground bank: material name '" + name + "' cannot name an HDF5 group");
    write_material(file, "/materials/" + name, bank.materials[i], i);
  }
  write_sweep_status(file, bank.sweep);
  write_provenance(file, command, config_toml, n_ranks);
  file.commit();
}

model::GroundBank read_ground_bank(const std::string& path) {
  auto file = File::open(path);
  check_header(file, kGroundBankFormat, kGroundBankFormatVersion);
  model::GroundBank bank;
  bank.c0_m_s = read_positive(file, "/air", "c0_m_s");
  bank.rho0_kg_m3 = read_positive(file, "/air", "rho0_kg_m3");
  const auto names = group_members(file, "/materials");
  bank.materials.resize(names.size());
  std::vector<bool> taken(names.size(), false);
  for (const auto& name : names) {
    const std::string g = "/materials/" + name;
    const auto index = read_attribute<std::int32_t>(file, g, "index");
    if (index < 0 || static_cast<std::size_t>(index) >= names.size() || taken[static_cast<std::size_t>(index)])
      throw InputError(fmt::format("{}: attribute 'index' of '{}' = {}: not a free place among the {} materials", path, g,
                                   index, names.size()));
    taken[static_cast<std::size_t>(index)] = true;
    bank.materials[static_cast<std::size_t>(index)] = read_material(file, g, name);
  }
  bank.sweep = read_sweep_status(file);
  return bank;
}

void write_ground_task(File& file, const std::string& group, const std::vector<GroundSeries>& row) {
  create_group(file, group);
  write_series(file, group, row);
}

std::vector<GroundSeries> read_ground_task(const File& file, const std::string& group, std::size_t n_eta) {
  return read_series(file, group, n_eta);
}

}  // namespace clatter::io
