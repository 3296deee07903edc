#include "io/modal_transfer.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.hpp"

namespace clatter::io {

void write_transfer(File& f, const std::string& g, const model::ModalTransfer& t, std::size_t n) {
  if (t.wavenumber_rad_m.size() != n || t.order.size() != n || t.boundary_residual.size() != n || t.normal_fraction.size() != n ||
      t.amplification.size() != n || t.source_depth.size() != n || t.attempts.size() != n || t.sources.size() != n ||
      t.coefficients.size() != 2 * t.offset(n))
    throw std::invalid_argument("modal entry: transfer arrays of unequal length");
  create_group(f, g);
  write_dataset<double>(f, g + "/wavenumber_rad_m", t.wavenumber_rad_m, {n}, "rad/m", true);
  write_dataset<std::int32_t>(f, g + "/order", t.order, {n}, "1", true);
  write_dataset<double>(f, g + "/coefficients", t.coefficients, {t.coefficients.size() / 2, 2}, "Pa", true);
  write_dataset<double>(f, g + "/boundary_residual", t.boundary_residual, {n}, "1", true);
  write_dataset<double>(f, g + "/normal_fraction", t.normal_fraction, {n}, "1", true);
  write_dataset<double>(f, g + "/amplification", t.amplification, {n}, "1", true);
  write_dataset<double>(f, g + "/source_depth", t.source_depth, {n}, "1", true);
  write_dataset<std::int32_t>(f, g + "/attempts", t.attempts, {n}, "1", true);
  write_dataset<std::int32_t>(f, g + "/sources", t.sources, {n}, "1", true);
}

model::ModalTransfer read_transfer(const File& f, const std::string& g, std::size_t modes) {
  const auto n = static_cast<long long>(modes);
  model::ModalTransfer t;
  t.wavenumber_rad_m = read_dataset<double>(f, g + "/wavenumber_rad_m", {n}, "rad/m");
  t.order = read_dataset<std::int32_t>(f, g + "/order", {n}, "1");
  t.boundary_residual = read_dataset<double>(f, g + "/boundary_residual", {n}, "1");
  t.normal_fraction = read_dataset<double>(f, g + "/normal_fraction", {n}, "1");
  t.amplification = read_dataset<double>(f, g + "/amplification", {n}, "1");
  t.source_depth = read_dataset<double>(f, g + "/source_depth", {n}, "1");
  t.attempts = read_dataset<std::int32_t>(f, g + "/attempts", {n}, "1");
  t.sources = read_dataset<std::int32_t>(f, g + "/sources", {n}, "1");
  auto bad = [&](const std::string& what) { return InputError(fmt::format("{}: {}: {}", f.path(), g, what)); };
  for (std::size_t i = 0; i < modes; ++i) {
    if (t.order[i] < 0 || t.order[i] > 2000) throw bad(fmt::format("order[{}] = {} is not an order in 0..2000", i, t.order[i]));
    if (!(t.wavenumber_rad_m[i] > 0)) throw bad(fmt::format("wavenumber_rad_m[{}] = {} is not positive", i, t.wavenumber_rad_m[i]));
    if (!(t.boundary_residual[i] >= 0)) throw bad(fmt::format("boundary_residual[{}] = {} is not a residual", i, t.boundary_residual[i]));
  }
  const auto pairs = static_cast<long long>(t.offset(modes));
  t.coefficients = read_dataset<double>(f, g + "/coefficients", {pairs, 2}, "Pa");
  for (double c : t.coefficients)
    if (!std::isfinite(c)) throw bad("coefficients holds a non-finite value");
  return t;
}

void write_transfer_header(File& f, const std::string& g, const model::TransferSettings& h) {
  create_group(f, g);
  write_attribute(f, g, "method", h.method);
  write_attribute<double>(f, g, "sound_speed_m_s", h.sound_speed_m_s);
  write_attribute<double>(f, g, "air_density_kg_m3", h.air_density_kg_m3);
  write_attribute<double>(f, g, "points_per_source", h.points_per_source);
  write_attribute<double>(f, g, "sources_per_wavelength", h.sources_per_wavelength);
  write_attribute<double>(f, g, "residual_target", h.residual_target);
  write_attribute<double>(f, g, "tail_tolerance", h.tail_tolerance);
}

model::TransferSettings read_transfer_header(const File& f, const std::string& g) {
  model::TransferSettings h;  // the kernel's constants, not stored, keep their defaults
  h.method = read_string_attribute(f, g, "method");
  h.sound_speed_m_s = read_attribute<double>(f, g, "sound_speed_m_s");
  h.air_density_kg_m3 = read_attribute<double>(f, g, "air_density_kg_m3");
  h.points_per_source = read_attribute<double>(f, g, "points_per_source");
  h.sources_per_wavelength = read_attribute<double>(f, g, "sources_per_wavelength");
  h.residual_target = read_attribute<double>(f, g, "residual_target");
  h.tail_tolerance = read_attribute<double>(f, g, "tail_tolerance");
  if (!(h.sound_speed_m_s > 0) || !(h.air_density_kg_m3 > 0))
    throw InputError(fmt::format("{}: {}: sound speed {} m/s, density {} kg/m^3: not an acoustic medium", f.path(), g,
                                 h.sound_speed_m_s, h.air_density_kg_m3));
  return h;
}

}  // namespace clatter::io
