#include "io/object_bank.hpp"

#include <fmt/format.h>

#include <set>

#include "core/errors.hpp"
#include "io/modal_bank.hpp"
#include "io/modal_transfer.hpp"
#include "io/provenance.hpp"
#include "io/sweep_files.hpp"

namespace clatter::io {

void write_object_entry(File& f, const std::string& g, const model::ObjectEntry& e, bool with_cost) {
  write_modal_entry(f, g, e.modal, with_cost);
  write_attribute(f, g, "key", e.key);
  write_attribute(f, g, "mesh_hash", e.mesh_hash);
  write_attribute(f, g, "source", e.source);
  write_material(f, g + "/material", e.material);
  write_attribute<double>(f, g, "mass_kg", e.mass_kg);
  write_attribute<double>(f, g, "volume_m3", e.volume_m3);
  write_attribute<double>(f, g, "radius_m", e.radius_m);
  write_attribute<double>(f, g, "min_thickness_m", e.min_thickness_m);
  write_attribute<double>(f, g, "surface_area_m2", e.surface_area_m2);
  write_attribute<std::int64_t>(f, g, "curved_edges", e.curved_edges);
  write_dataset<double>(f, g + "/centre_m", e.centre_m, {3}, "m", true);
}

model::ObjectEntry read_object_entry(const File& f, const std::string& g) {
  model::ObjectEntry e;
  e.modal = read_modal_entry(f, g);
  e.key = read_string_attribute(f, g, "key");
  e.mesh_hash = read_string_attribute(f, g, "mesh_hash");
  e.source = read_string_attribute(f, g, "source");
  e.material = read_material(f, g + "/material");
  e.mass_kg = read_attribute<double>(f, g, "mass_kg");
  e.volume_m3 = read_attribute<double>(f, g, "volume_m3");
  e.radius_m = read_attribute<double>(f, g, "radius_m");
  e.min_thickness_m = read_attribute<double>(f, g, "min_thickness_m");
  e.surface_area_m2 = read_attribute<double>(f, g, "surface_area_m2");
  e.curved_edges = read_attribute<std::int64_t>(f, g, "curved_edges");
  const auto centre = read_dataset<double>(f, g + "/centre_m", {3}, "m");
  std::copy(centre.begin(), centre.end(), e.centre_m.begin());
  auto bad = [&](const std::string& what) { return InputError(fmt::format("{}: {}: {}", f.path(), g, what)); };
  if (e.key != e.mesh_hash + "-" + e.material.name)
    throw bad(fmt::format("key '{}' is not mesh_hash-material ('{}-{}')", e.key, e.mesh_hash, e.material.name));
  if (!(e.mass_kg > 0) || !(e.volume_m3 > 0) || !(e.radius_m > 0))
    throw bad(fmt::format("mass_kg {}, volume_m3 {}, radius_m {}: not a solid", e.mass_kg, e.volume_m3, e.radius_m));
  for (const auto& x : e.modal.surface_nodes_m)
    if (std::hypot(x[0], x[1], x[2]) > e.radius_m * (1 + 1e-9))
      throw bad(fmt::format("a surface node lies {} m from the centre, beyond radius_m {}", std::hypot(x[0], x[1], x[2]),
                            e.radius_m));
  return e;
}

void write_object_bank(const std::string& path, const model::ObjectBank& bank, const std::string& command,
                       const std::string& config_toml, int n_ranks) {
  const auto& h = bank.header;
  auto file = File::create(path);
  write_header(file, kObjectBankFormat, kObjectBankFormatVersion);
  create_group(file, "/settings");
  write_attribute<double>(file, "/settings", "f_max_hz", h.f_max_hz);
  write_attribute<double>(file, "/settings", "elements_per_wavelength", h.elements_per_wavelength);
  write_attribute<std::int32_t>(file, "/settings", "elements_through_thickness", h.elements_through_thickness);
  write_attribute<double>(file, "/settings", "proxy_above_hz", h.proxy_above_hz);
  write_attribute<double>(file, "/settings", "cluster_gap", h.solve.cluster_gap);
  write_attribute<double>(file, "/settings", "degenerate_gap", h.solve.degenerate_gap);
  write_attribute<double>(file, "/settings", "solver_tolerance", h.solve.tolerance);
  write_attribute<double>(file, "/settings", "residual_limit", h.solve.residual_limit);
  write_attribute<std::int32_t>(file, "/settings", "ranks_per_task", h.ranks_per_task);
  write_attribute(file, "/settings", "solver_libraries", h.solver_libraries);
  write_transfer_header(file, "/settings/transfer", h.transfer);
  create_group(file, "/entries");
  for (std::size_t i = 0; i < bank.entries.size(); ++i)
    write_object_entry(file, fmt::format("/entries/{:04d}", i), bank.entries[i], false);
  write_sweep_status(file, bank.sweep);
  write_provenance(file, command, config_toml, n_ranks);
  for (std::size_t i = 0; i < bank.entries.size(); ++i)
    write_modal_entry_cost(file, fmt::format("/provenance/run/entries/{:04d}", i), bank.entries[i].modal.cost);
  file.commit();
}

model::ObjectBank read_object_bank(const std::string& path) {
  auto file = File::open(path);
  check_header(file, kObjectBankFormat, kObjectBankFormatVersion);
  model::ObjectBank bank;
  auto& h = bank.header;
  h.f_max_hz = read_attribute<double>(file, "/settings", "f_max_hz");
  h.elements_per_wavelength = read_attribute<double>(file, "/settings", "elements_per_wavelength");
  h.elements_through_thickness = read_attribute<std::int32_t>(file, "/settings", "elements_through_thickness");
  h.proxy_above_hz = read_attribute<double>(file, "/settings", "proxy_above_hz");
  h.solve.cluster_gap = read_attribute<double>(file, "/settings", "cluster_gap");
  h.solve.degenerate_gap = read_attribute<double>(file, "/settings", "degenerate_gap");
  h.solve.tolerance = read_attribute<double>(file, "/settings", "solver_tolerance");
  h.solve.residual_limit = read_attribute<double>(file, "/settings", "residual_limit");
  h.ranks_per_task = read_attribute<std::int32_t>(file, "/settings", "ranks_per_task");
  h.solver_libraries = read_string_attribute(file, "/settings", "solver_libraries");
  h.transfer = read_transfer_header(file, "/settings/transfer");
  std::set<std::string> keys;
  for (const std::string& name : group_members(file, "/entries")) {
    const std::string g = "/entries/" + name;
    model::ObjectEntry e = read_object_entry(file, g);
    check_modal_entry_solve(file, g, e.modal, h.solve);
    if (!keys.insert(e.key).second) throw InputError(fmt::format("{}: {}: key '{}' appears twice", path, g, e.key));
    const std::string cost = "/provenance/run/entries/" + name;
    if (exists(file, cost)) e.modal.cost = read_modal_entry_cost(file, cost);
    bank.entries.push_back(std::move(e));
  }
  bank.sweep = read_sweep_status(file);
  return bank;
}

}  // namespace clatter::io
