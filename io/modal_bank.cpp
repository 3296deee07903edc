#include "io/modal_bank.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/errors.hpp"
#include "io/modal_transfer.hpp"
#include "io/provenance.hpp"
#include "io/sweep_files.hpp"

namespace clatter::io {
namespace {

// kernels/modal/mode_basis.hpp kReferenceFields (io/ does not include kernels/).
constexpr std::int32_t kernels_reference_fields = 60;

using model::ModalEntry;

template <class T, std::size_t N>
std::vector<T> flatten(const std::vector<std::array<T, N>>& rows) {
  std::vector<T> out;
  out.reserve(rows.size() * N);
  for (const auto& r : rows) out.insert(out.end(), r.begin(), r.end());
  return out;
}

template <class T, std::size_t N>
std::vector<std::array<T, N>> unflatten(const std::vector<T>& flat) {
  std::vector<std::array<T, N>> out(flat.size() / N);
  for (std::size_t i = 0; i < out.size(); ++i) std::copy_n(flat.begin() + static_cast<long>(i * N), N, out[i].begin());
  return out;
}

void write_mesh_stats(File& f, const std::string& g, const model::ModalMeshStats& m) {
  create_group(f, g);
  write_attribute<std::int64_t>(f, g, "elements", m.elements);
  write_attribute<std::int64_t>(f, g, "nodes", m.nodes);
  write_attribute<std::int64_t>(f, g, "dofs", m.dofs);
  write_attribute<double>(f, g, "edge_length_m", m.edge_length_m);
  write_attribute<double>(f, g, "max_radius_edge", m.max_radius_edge);
  write_attribute<double>(f, g, "mean_radius_edge", m.mean_radius_edge);
  write_attribute<double>(f, g, "min_dihedral_deg", m.min_dihedral_deg);
  write_attribute<double>(f, g, "max_dihedral_deg", m.max_dihedral_deg);
  write_attribute<double>(f, g, "min_jacobian_ratio", m.min_jacobian_ratio);
}

model::ModalMeshStats read_mesh_stats(const File& f, const std::string& g) {
  model::ModalMeshStats m;
  m.elements = read_attribute<std::int64_t>(f, g, "elements");
  m.nodes = read_attribute<std::int64_t>(f, g, "nodes");
  m.dofs = read_attribute<std::int64_t>(f, g, "dofs");
  m.edge_length_m = read_attribute<double>(f, g, "edge_length_m");
  m.max_radius_edge = read_attribute<double>(f, g, "max_radius_edge");
  m.mean_radius_edge = read_attribute<double>(f, g, "mean_radius_edge");
  m.min_dihedral_deg = read_attribute<double>(f, g, "min_dihedral_deg");
  m.max_dihedral_deg = read_attribute<double>(f, g, "max_dihedral_deg");
  m.min_jacobian_ratio = read_attribute<double>(f, g, "min_jacobian_ratio");
  return m;
}

void write_solve_record(File& f, const std::string& g, const model::ModalSolveRecord& s) {
  create_group(f, g);
  write_attribute<double>(f, g, "lambda_lo_rad2_s2", s.lambda_lo);
  write_attribute<double>(f, g, "lambda_hi_rad2_s2", s.lambda_hi);
  write_attribute<std::int64_t>(f, g, "below_lo", s.below_lo);
  write_attribute<std::int64_t>(f, g, "below_hi", s.below_hi);
  write_attribute<std::int64_t>(f, g, "found_in_interval", s.found_in_interval);
  write_attribute<std::int64_t>(f, g, "shifts", s.shifts);
  write_attribute<double>(f, g, "first_mode_estimate_hz", s.first_mode_estimate_hz);
  write_attribute(f, g, "solver_options", s.solver_options);
}

model::ModalSolveRecord read_solve_record(const File& f, const std::string& g) {
  model::ModalSolveRecord s;
  s.lambda_lo = read_attribute<double>(f, g, "lambda_lo_rad2_s2");
  s.lambda_hi = read_attribute<double>(f, g, "lambda_hi_rad2_s2");
  s.below_lo = read_attribute<std::int64_t>(f, g, "below_lo");
  s.below_hi = read_attribute<std::int64_t>(f, g, "below_hi");
  s.found_in_interval = read_attribute<std::int64_t>(f, g, "found_in_interval");
  s.shifts = read_attribute<std::int64_t>(f, g, "shifts");
  s.first_mode_estimate_hz = read_attribute<double>(f, g, "first_mode_estimate_hz");
  s.solver_options = read_string_attribute(f, g, "solver_options");
  return s;
}

void write_band(File& f, const std::string& g, const model::ModalBand& b) {
  create_group(f, g);
  write_attribute<double>(f, g, "f_max_hz", b.f_max_hz);
  write_attribute<double>(f, g, "mesh_error", b.mesh_error);
  write_attribute<double>(f, g, "keep_to_hz", b.keep_to_hz);
}

model::ModalBand read_band(const File& f, const std::string& g) {
  return {read_attribute<double>(f, g, "f_max_hz"), read_attribute<double>(f, g, "mesh_error"),
          read_attribute<double>(f, g, "keep_to_hz")};
}

void write_symmetry(File& f, const std::string& g, const model::ModalSymmetry& s) {
  create_group(f, g);
  write_attribute(f, g, "kind", s.kind);
  write_attribute<std::int32_t>(f, g, "axis", s.axis);
  write_attribute<double>(f, g, "order_defect", s.order_defect);
  write_attribute<std::int32_t>(f, g, "incomplete", s.incomplete);
}

model::ModalSymmetry read_symmetry(const File& f, const std::string& g) {
  return {read_string_attribute(f, g, "kind"), read_attribute<std::int32_t>(f, g, "axis"),
          read_attribute<double>(f, g, "order_defect"), read_attribute<std::int32_t>(f, g, "incomplete")};
}

void write_cost(File& f, const std::string& g, const model::ModalEntryCost& c) {
  create_group(f, g);
  write_attribute<double>(f, g, "mesh_s", c.mesh_s);
  write_attribute<double>(f, g, "assembly_s", c.assembly_s);
  write_attribute<double>(f, g, "estimate_s", c.estimate_s);
  write_attribute<double>(f, g, "solve_s", c.solve_s);
  write_attribute<double>(f, g, "total_s", c.total_s);
  write_attribute<double>(f, g, "transfer_s", c.transfer_s);
  write_attribute<double>(f, g, "transfer_core_s", c.transfer_core_s);
  write_attribute<double>(f, g, "factor_memory_mb", c.factor_memory_mb);
  write_attribute<double>(f, g, "memory_max_mb", c.memory_max_mb);
  write_attribute<std::int32_t>(f, g, "ranks", c.ranks);
}

model::ModalEntryCost read_cost(const File& f, const std::string& g) {
  model::ModalEntryCost c;
  c.mesh_s = read_attribute<double>(f, g, "mesh_s");
  c.assembly_s = read_attribute<double>(f, g, "assembly_s");
  c.estimate_s = read_attribute<double>(f, g, "estimate_s");
  c.solve_s = read_attribute<double>(f, g, "solve_s");
  c.total_s = read_attribute<double>(f, g, "total_s");
  c.transfer_s = read_attribute<double>(f, g, "transfer_s");
  c.transfer_core_s = read_attribute<double>(f, g, "transfer_core_s");
  c.factor_memory_mb = read_attribute<double>(f, g, "factor_memory_mb");
  c.memory_max_mb = read_attribute<double>(f, g, "memory_max_mb");
  c.ranks = read_attribute<std::int32_t>(f, g, "ranks");
  return c;
}

// The entry's arrays, without its cost (which a bank keeps in provenance).
void write_entry_content(File& f, const std::string& g, const ModalEntry& e) {
  const std::size_t n = e.modes(), ns = e.surface_nodes_m.size();
  if (e.damping_ratios.size() != n || e.cluster.size() != n || e.multiplet.size() != n ||
      e.symmetry_order.size() != n || e.relative_residuals.size() != n || e.shapes.size() != n * ns * 3)
    throw std::invalid_argument("modal entry: per-mode arrays of unequal length");
  create_group(f, g);
  write_attribute<std::uint32_t>(f, g, "sample", e.sample);
  write_dataset<double>(f, g + "/axes_m", e.axes_m, {3}, "m", true);
  write_dataset<double>(f, g + "/frequencies_hz", e.frequencies_hz, {n}, "Hz", true);
  write_dataset<double>(f, g + "/damping_ratios", e.damping_ratios, {n}, "1", true);
  write_dataset<std::int32_t>(f, g + "/cluster", e.cluster, {n}, "1", true);
  write_dataset<std::int32_t>(f, g + "/multiplet", e.multiplet, {n}, "1", true);
  write_dataset<std::int32_t>(f, g + "/symmetry_order", e.symmetry_order, {n}, "1", true);
  write_dataset<double>(f, g + "/relative_residuals", e.relative_residuals, {n}, "1", true);
  write_dataset<double>(f, g + "/surface/nodes_m", flatten(e.surface_nodes_m), {ns, 3}, "m", true);
  write_dataset<std::int32_t>(f, g + "/surface/faces", flatten(e.surface_faces), {e.surface_faces.size(), 6}, "1", true);
  write_dataset<double>(f, g + "/shapes", e.shapes, {n, ns, 3}, "kg^-1/2", true);
  write_transfer(f, g + "/transfer", e.transfer, n);
  write_mesh_stats(f, g + "/mesh", e.mesh);
  write_solve_record(f, g + "/solve", e.solve);
  write_band(f, g + "/band", e.band);
  write_symmetry(f, g + "/symmetry", e.symmetry);
}

// Everything a reader relies on: shapes agree, frequencies ascend, indices are in range.
void check_entry(const File& f, const std::string& g, const ModalEntry& e) {
  auto bad = [&](const std::string& what) { return InputError(fmt::format("{}: {}: {}", f.path(), g, what)); };
  const std::size_t n = e.modes();
  std::int32_t highest = -1;              // the multiplets numbered so far
  std::vector<std::size_t> first_member;  // per multiplet
  for (std::size_t i = 0; i < n; ++i) {
    if (!(e.frequencies_hz[i] > 0) || !std::isfinite(e.frequencies_hz[i]))
      throw bad(fmt::format("frequencies_hz[{}] = {} is not a positive frequency", i, e.frequencies_hz[i]));
    if (i > 0 && e.frequencies_hz[i] < e.frequencies_hz[i - 1])
      throw bad(fmt::format("frequencies_hz[{}] = {} is below frequencies_hz[{}]: not ascending", i,
                            e.frequencies_hz[i], i - 1));
    if (e.cluster[i] != (i == 0 ? 0 : e.cluster[i - 1]) && e.cluster[i] != (i == 0 ? 0 : e.cluster[i - 1] + 1))
      throw bad(fmt::format("cluster[{}] = {} does not number the clusters in order", i, e.cluster[i]));
    if (e.multiplet[i] < 0 || e.multiplet[i] > highest + 1)
      throw bad(fmt::format("multiplet[{}] = {} does not number the multiplets by their lowest members", i, e.multiplet[i]));
    highest = std::max(highest, e.multiplet[i]);
    if (e.symmetry_order[i] < -1) throw bad(fmt::format("symmetry_order[{}] = {} is below -1", i, e.symmetry_order[i]));
    const auto first = static_cast<std::size_t>(e.multiplet[i]);
    if (first == first_member.size()) first_member.push_back(i);
    const std::size_t j = first_member[first];
    if (e.cluster[j] != e.cluster[i] || e.symmetry_order[j] != e.symmetry_order[i])
      throw bad(fmt::format("modes {} and {} share multiplet {} but not their cluster and order", j, i, e.multiplet[i]));
    if (!(e.relative_residuals[i] >= 0) || !(e.damping_ratios[i] >= 0))
      throw bad(fmt::format("mode {}: residual {} or damping {} is not a non-negative number", i,
                            e.relative_residuals[i], e.damping_ratios[i]));
  }
  const auto ns = static_cast<std::int32_t>(e.surface_nodes_m.size());
  for (std::size_t t = 0; t < e.surface_faces.size(); ++t)
    for (std::int32_t v : e.surface_faces[t])
      if (v < 0 || v >= ns) throw bad(fmt::format("surface/faces[{}] names node {} of {}", t, v, ns));
  for (double x : e.shapes)
    if (!std::isfinite(x)) throw bad("shapes holds a non-finite value");
  const auto& b = e.band;
  if (!(b.f_max_hz > 0) || !(b.mesh_error >= 0) || !(b.keep_to_hz >= b.f_max_hz) || !std::isfinite(b.keep_to_hz))
    throw bad(fmt::format("band: f_max_hz {}, mesh_error {}, keep_to_hz {}: not a band", b.f_max_hz, b.mesh_error,
                          b.keep_to_hz));
  if (std::abs(b.keep_to_hz - b.f_max_hz * (1 + b.mesh_error)) > 1e-12 * b.keep_to_hz)
    throw bad(fmt::format("band: keep_to_hz {} is not f_max_hz {} (1 + mesh_error {})", b.keep_to_hz, b.f_max_hz,
                          b.mesh_error));
  if (e.symmetry.kind != "sphere" && e.symmetry.kind != "spheroid" && e.symmetry.kind != "none")
    throw bad(fmt::format("symmetry/kind '{}' is not sphere, spheroid or none", e.symmetry.kind));
}

// What the bank's settings promise of every entry: residuals within the limit, the count check
// passed, exactly the 6 rigid motions below the interval.
void check_against_settings(const File& f, const std::string& g, const ModalEntry& e, const model::ModalSolveSettings& solve) {
  for (std::size_t i = 0; i < e.modes(); ++i)
    if (e.relative_residuals[i] > solve.residual_limit)
      throw InputError(fmt::format("{}: {}: mode {} has relative residual {} above the bank's residual_limit {}",
                                   f.path(), g, i, e.relative_residuals[i], solve.residual_limit));
  if (e.solve.found_in_interval != e.solve.below_hi - e.solve.below_lo || e.solve.below_lo != 6 ||
      static_cast<std::int64_t>(e.modes()) > e.solve.found_in_interval)
    throw InputError(fmt::format("{}: {}/solve: found_in_interval {}, below_lo {}, below_hi {} for {} modes: the "
                                 "count check does not hold", f.path(), g, e.solve.found_in_interval, e.solve.below_lo,
                                 e.solve.below_hi, e.modes()));
  // The guarantee: the count-checked interval reaches past the band's keep_to, every mode below it stored.
  if (e.solve.lambda_hi < std::pow(2 * M_PI * e.band.keep_to_hz, 2) * (1 - 1e-12))
    throw InputError(fmt::format("{}: {}: the solved interval ends at {} Hz, below the band's keep_to_hz {}", f.path(), g,
                                 std::sqrt(e.solve.lambda_hi) / (2 * M_PI), e.band.keep_to_hz));
}

}  // namespace

void write_modal_entry(File& file, const std::string& group, const ModalEntry& entry, bool with_cost) {
  write_entry_content(file, group, entry);
  if (with_cost) write_cost(file, group + "/cost", entry.cost);
}

void write_modal_entry_cost(File& file, const std::string& group, const model::ModalEntryCost& cost) {
  write_cost(file, group, cost);
}

model::ModalEntryCost read_modal_entry_cost(const File& file, const std::string& group) { return read_cost(file, group); }

void write_material(File& file, const std::string& g, const model::Material& m) {
  if (!m.damping) throw std::invalid_argument("modal model: material '" + m.name + "' has no Rayleigh damping");
  create_group(file, g);
  write_attribute(file, g, "name", m.name);
  write_attribute(file, g, "source", m.source);
  write_attribute<double>(file, g, "rho_kg_m3", m.rho_kg_m3);
  write_attribute<double>(file, g, "youngs_pa", m.youngs_pa);
  write_attribute<double>(file, g, "poisson", m.poisson);
  write_attribute<double>(file, g, "rayleigh_alpha_1_s", m.damping->alpha_1_s);
  write_attribute<double>(file, g, "rayleigh_beta_s", m.damping->beta_s);
}

model::Material read_material(const File& file, const std::string& g) {
  model::Material m;
  m.name = read_string_attribute(file, g, "name");
  m.source = read_string_attribute(file, g, "source");
  m.rho_kg_m3 = read_attribute<double>(file, g, "rho_kg_m3");
  m.youngs_pa = read_attribute<double>(file, g, "youngs_pa");
  m.poisson = read_attribute<double>(file, g, "poisson");
  m.damping = model::RayleighDamping{read_attribute<double>(file, g, "rayleigh_alpha_1_s"),
                                     read_attribute<double>(file, g, "rayleigh_beta_s")};
  if (const std::string bad = model::check_material(m); !bad.empty())
    throw InputError(fmt::format("{}: {}: {}: not an elastic material", file.path(), g, bad));
  return m;
}

void check_modal_entry_solve(const File& f, const std::string& g, const ModalEntry& e, const model::ModalSolveSettings& s) {
  check_against_settings(f, g, e, s);
}

ModalEntry read_modal_entry(const File& f, const std::string& g) {
  ModalEntry e;
  e.sample = read_attribute<std::uint32_t>(f, g, "sample");
  const auto axes = read_dataset<double>(f, g + "/axes_m", {3}, "m");
  std::copy(axes.begin(), axes.end(), e.axes_m.begin());
  e.frequencies_hz = read_dataset<double>(f, g + "/frequencies_hz", {-1}, "Hz");
  const auto n = static_cast<long long>(e.frequencies_hz.size());
  e.damping_ratios = read_dataset<double>(f, g + "/damping_ratios", {n}, "1");
  e.cluster = read_dataset<std::int32_t>(f, g + "/cluster", {n}, "1");
  e.multiplet = read_dataset<std::int32_t>(f, g + "/multiplet", {n}, "1");
  e.symmetry_order = read_dataset<std::int32_t>(f, g + "/symmetry_order", {n}, "1");
  e.relative_residuals = read_dataset<double>(f, g + "/relative_residuals", {n}, "1");
  Dims dims;
  e.surface_nodes_m = unflatten<double, 3>(read_dataset<double>(f, g + "/surface/nodes_m", {-1, 3}, "m", &dims));
  const auto ns = static_cast<long long>(dims[0]);
  e.surface_faces = unflatten<std::int32_t, 6>(read_dataset<std::int32_t>(f, g + "/surface/faces", {-1, 6}, "1"));
  e.shapes = read_dataset<double>(f, g + "/shapes", {n, ns, 3}, "kg^-1/2");
  e.transfer = read_transfer(f, g + "/transfer", e.frequencies_hz.size());
  e.mesh = read_mesh_stats(f, g + "/mesh");
  e.solve = read_solve_record(f, g + "/solve");
  e.band = read_band(f, g + "/band");
  e.symmetry = read_symmetry(f, g + "/symmetry");
  if (exists(f, g + "/cost")) e.cost = read_cost(f, g + "/cost");
  check_entry(f, g, e);
  return e;
}

void write_modal_bank(const std::string& path, const model::ModalBank& bank, const std::string& command,
                      const std::string& config_toml, int n_ranks) {
  const auto& h = bank.header;
  auto file = File::create(path);
  write_header(file, kModalBankFormat, kModalBankFormatVersion);
  write_material(file, "/material", h.material);
  create_group(file, "/settings");
  write_attribute<double>(file, "/settings", "f_max_multiple", h.solve.f_max_multiple);
  write_attribute<double>(file, "/settings", "band_top_hz", h.band.top_hz);
  write_attribute<double>(file, "/settings", "band_largest_piece_m", h.band.largest_piece_m);
  write_attribute<double>(file, "/settings", "band_proxy_above_hz", h.band.proxy_above_hz);
  write_attribute<double>(file, "/settings", "band_max_multiple", h.band.max_multiple);
  write_attribute<double>(file, "/settings", "elements_per_wavelength", h.elements_per_wavelength);
  write_attribute<double>(file, "/settings", "min_ratio", h.min_ratio);
  write_attribute<double>(file, "/settings", "cigar_ratio", h.cigar_ratio);
  write_attribute<double>(file, "/settings", "cluster_gap", h.solve.cluster_gap);
  write_attribute<double>(file, "/settings", "degenerate_gap", h.solve.degenerate_gap);
  write_attribute<std::int32_t>(file, "/settings", "reference_fields", kernels_reference_fields);
  write_attribute<double>(file, "/settings", "coarse_edge_m", h.coarse_edge_m);
  write_attribute<double>(file, "/settings", "elements_through_thickness", h.elements_through_thickness);
  write_attribute<double>(file, "/settings", "coarse_elements_through_thickness", h.coarse_elements_through_thickness);
  write_attribute<double>(file, "/settings", "layered_below_ratio", h.layered_below_ratio);
  write_attribute<std::int32_t>(file, "/settings", "layers", h.layers);
  write_attribute<std::int32_t>(file, "/settings", "coarse_layers", h.coarse_layers);
  write_attribute<double>(file, "/settings", "solver_tolerance", h.solve.tolerance);
  write_attribute<double>(file, "/settings", "residual_limit", h.solve.residual_limit);
  write_attribute<std::int32_t>(file, "/settings", "ranks_per_task", h.ranks_per_task);
  write_attribute(file, "/settings", "solver_libraries", h.solver_libraries);
  write_transfer_header(file, "/settings/transfer", h.transfer);
  std::vector<double> axes;
  for (const auto& e : bank.entries) axes.insert(axes.end(), e.axes_m.begin(), e.axes_m.end());
  create_group(file, "/entries");
  write_dataset<double>(file, "/entries/axes_m", axes, {bank.entries.size(), 3}, "m", true);
  for (std::size_t i = 0; i < bank.entries.size(); ++i)
    write_entry_content(file, fmt::format("/entries/{:04d}", i), bank.entries[i]);
  write_sweep_status(file, bank.sweep);
  write_provenance(file, command, config_toml, n_ranks);
  for (std::size_t i = 0; i < bank.entries.size(); ++i)
    write_cost(file, fmt::format("/provenance/run/entries/{:04d}", i), bank.entries[i].cost);
  file.commit();
}

model::ModalBank read_modal_bank(const std::string& path) {
  auto file = File::open(path);
  check_header(file, kModalBankFormat, kModalBankFormatVersion);
  model::ModalBank bank;
  auto& h = bank.header;
  h.material = read_material(file, "/material");
  // The solve's settings as stored; max_iterations and nev_per_shift are not (they change the work,
  // not the result) and read back as 0.
  h.solve.f_max_multiple = read_attribute<double>(file, "/settings", "f_max_multiple");
  h.band.top_hz = read_attribute<double>(file, "/settings", "band_top_hz");
  h.band.largest_piece_m = read_attribute<double>(file, "/settings", "band_largest_piece_m");
  h.band.proxy_above_hz = read_attribute<double>(file, "/settings", "band_proxy_above_hz");
  h.band.max_multiple = read_attribute<double>(file, "/settings", "band_max_multiple");
  h.elements_per_wavelength = read_attribute<double>(file, "/settings", "elements_per_wavelength");
  h.min_ratio = read_attribute<double>(file, "/settings", "min_ratio");
  // Banks before the patch had two corners: its cigar lay at a/c = min_ratio too.
  h.cigar_ratio = has_attribute(file, "/settings", "cigar_ratio") ? read_attribute<double>(file, "/settings", "cigar_ratio")
                                                                  : h.min_ratio;
  h.solve.cluster_gap = read_attribute<double>(file, "/settings", "cluster_gap");
  h.solve.degenerate_gap = read_attribute<double>(file, "/settings", "degenerate_gap");
  h.coarse_edge_m = read_attribute<double>(file, "/settings", "coarse_edge_m");
  // Banks before the setting had both caps fixed at 3 elements through the thinnest axis.
  for (auto [name, value] : {std::pair{"elements_through_thickness", &h.elements_through_thickness},
                             std::pair{"coarse_elements_through_thickness", &h.coarse_elements_through_thickness}})
    *value = has_attribute(file, "/settings", name) ? read_attribute<double>(file, "/settings", name) : 3.0;
  // Banks before the layered mesher meshed every entry by TetGen's fill.
  h.layered_below_ratio = has_attribute(file, "/settings", "layered_below_ratio")
                              ? read_attribute<double>(file, "/settings", "layered_below_ratio") : 0.0;
  if (h.layered_below_ratio > 0) {
    h.layers = read_attribute<std::int32_t>(file, "/settings", "layers");
    h.coarse_layers = read_attribute<std::int32_t>(file, "/settings", "coarse_layers");
  }
  h.solve.tolerance = read_attribute<double>(file, "/settings", "solver_tolerance");
  h.solve.residual_limit = read_attribute<double>(file, "/settings", "residual_limit");
  h.ranks_per_task = read_attribute<std::int32_t>(file, "/settings", "ranks_per_task");
  h.solver_libraries = read_string_attribute(file, "/settings", "solver_libraries");
  h.transfer = read_transfer_header(file, "/settings/transfer");
  Dims dims;
  const auto axes = read_dataset<double>(file, "/entries/axes_m", {-1, 3}, "m", &dims);
  for (std::size_t i = 0; i < dims[0]; ++i) {
    bank.entries.push_back(read_modal_entry(file, fmt::format("/entries/{:04d}", i)));
    if (!std::equal(axes.begin() + static_cast<long>(3 * i), axes.begin() + static_cast<long>(3 * i + 3),
                    bank.entries.back().axes_m.begin()))
      throw InputError(fmt::format("{}: /entries/{:04d}/axes_m differs from row {} of /entries/axes_m", path, i, i));
    check_against_settings(file, fmt::format("/entries/{:04d}", i), bank.entries.back(), h.solve);
    const std::string cost = fmt::format("/provenance/run/entries/{:04d}", i);
    if (exists(file, cost)) bank.entries.back().cost = read_cost(file, cost);
  }
  bank.sweep = read_sweep_status(file);
  return bank;
}

}  // namespace clatter::io
