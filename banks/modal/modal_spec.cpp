#include "banks/modal/modal_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "io/materials.hpp"
#include "io/text_file.hpp"
#include "kernels/modal/patch_sampling.hpp"
#include "kernels/transfer/mode_transfer.hpp"

namespace clatter::jobs {
namespace {

// The transfer's defaults are the bank model's own (one definition, which the kernel takes).
const model::TransferSettings kTransfer{};

// A sweep of more entries is a mistake, not a bank (003's banks have tens).
constexpr std::size_t kMaxSamples = 10000;

// The default patch samples: `clatter-bank modal-samples` with the defaults (docs/modal.md
// "Sampling the patch"), a, b, c per row.
const io::RealList& default_samples() {
  static const io::RealList samples = {
#include "banks/modal/modal_default_samples.inc"
  };
  return samples;
}

}  // namespace

const io::Schema& modal_schema() {
  static const io::Schema schema{
      "clatter-bank modal: the modal bank (FEM modes of normalized ellipsoids, SLEPc spectrum slicing)",
      {
          {"material.name", std::string("glass"), "material of the bank: a table of material.table"},
          {"material.table", std::string(""), "materials file (TOML, docs/materials.md); empty: the built-in "
                                              "configs/materials.toml"},
          {"patch.min_ratio", 0.025, "smallest axis ratio a/c covered (the pancake corner, b = c)",
           {0.0, 1.0, true, true}},
          {"patch.cigar_ratio", 0.1, "b/c of the cigar corner (a = b); below patch.min_ratio it is raised to it (the "
                                     "patch is then a/c >= patch.min_ratio)",
           {0.0, 1.0, true, true}},
          {"patch.samples", default_samples(), "normalized semi-axes a <= b <= c, a^2 + b^2 + c^2 = 1 [m], one entry "
                                               "each (default: modal-samples output)", {0.0, 1.0, true}, {}, 3},
          {"modes.f_max_multiple", 2.0, "the smallest band: every entry keeps every mode up to at least this x f_1",
           {1.0, 64.0, true}},
          {"modes.top_hz", 20000.0, "the top of the audible band [Hz]", {0.0, 1e6, true}},
          {"modes.largest_piece_m", 0.3, "every piece up to this longest dimension (2c, in the bank's material) gets "
                                         "every mode up to modes.top_hz; 0: the band is f_max_multiple x f_1 [m]",
           {0.0, 100.0}},
          {"modes.proxy_above_hz", 2000.0, "pieces whose base frequency is below this ring with their own models "
                                           "(clatter-synth --proxy-above-hz, 003 section 5.4), so no entry needs a band "
                                           "beyond modes.top_hz / this x f_1; 0: no such bound [Hz]", {0.0, 1e6}},
          {"modes.max_multiple", 64.0, "the largest band multiple an entry may need (its cost's limit)",
           {1.0, 1000.0, true}},
          {"modes.cluster_gap", 5e-3, "relative gap below which neighbouring frequencies form one cluster",
           {0.0, 0.1, true}},
          {"mesh.elements_per_wavelength", 3.0, "h = shear wavelength at f_max / this", {1.0, 20.0}},
          {"mesh.coarse_edge_m", 0.25, "h of the pre-solve that estimates f_1 (sets h and the interval) [m]",
           {0.0, 1.0, true}},
          {"mesh.elements_through_thickness", 3.0, "and h at most 2 a / this (a the smallest semi-axis; 10-node "
           "tetrahedra hold bending exactly)", {0.5, 20.0}},
          {"mesh.coarse_elements_through_thickness", 1.5, "the same cap on the pre-solve's mesh", {0.5, 20.0}},
          {"mesh.layered_below_ratio", 0.19, "entries whose a / b is below this are meshed in layers through the "
           "thickness, with the in-plane h from the bending wavelength at f_max (docs/modal.md \"Thin entries\"); 0: "
           "every entry by TetGen's fill", {0.0, 1.0}},
          {"mesh.layers", std::int64_t{2}, "quadratic elements through the thickness of a layered entry", {1, 20}},
          {"mesh.coarse_layers", std::int64_t{1}, "the same on the pre-solve's mesh", {1, 20}},
          {"mesh.max_radius_edge", 3.0, "largest radius-edge ratio a mesh may have", {1.0, 100.0}},
          {"mesh.min_dihedral_deg", 5.0, "smallest dihedral angle a mesh may have [deg]", {0.0, 60.0}},
          {"mesh.min_jacobian_ratio", 0.2, "smallest min/max det J within a curved element", {0.0, 1.0, true}},
          {"solver.tolerance", 1e-11, "SLEPc's relative convergence tolerance (-eps_tol)", {1e-15, 1e-6}},
          {"solver.residual_limit", 1e-8, "largest relative residual ||Ku - lambda Mu|| / ||Ku|| a mode may have",
           {1e-15, 1e-3}},
          {"solver.max_iterations", std::int64_t{0}, "SLEPc restarts per shift; 0: SLEPc's default", {0, 1e6}},
          {"solver.nev_per_shift", std::int64_t{0}, "eigenpairs sought around each shift; 0: SLEPc's default",
           {0, 1e4}},
          {"medium.c_m_s", kTransfer.sound_speed_m_s, "speed of sound of the air the modes radiate into [m/s]",
           {0.0, 1e5, true}},
          {"medium.rho_kg_m3", kTransfer.air_density_kg_m3, "density of the air [kg/m^3]", {0.0, 1e5, true}},
          {"transfer.points_per_source", kTransfer.points_per_source,
           "fit points per source, along each grid angle (docs/transfer.md)", {1.0, 20.0}},
          {"transfer.sources_per_wavelength", kernels::transfer::kEllipsoidSourcesPerWavelength,
           "equivalent sources per air wavelength on their layer", {1.0, 20.0}},
          {"transfer.residual_target", kTransfer.residual_target,
           "boundary residual x normal fraction above which other source layers are tried", {1e-8, 1.0}},
          {"transfer.tail_tolerance", kTransfer.tail_tolerance, "far-field share (L2) the multipole truncation may drop",
           {1e-8, 0.1}},
      }};
  return schema;
}

model::ModalSolveSettings solve_settings(const io::Config& config) {
  model::ModalSolveSettings solve;
  solve.cluster_gap = config.real("modes.cluster_gap");
  solve.tolerance = config.real("solver.tolerance");
  solve.residual_limit = config.real("solver.residual_limit");
  solve.max_iterations = config.integer("solver.max_iterations");
  solve.nev_per_shift = config.integer("solver.nev_per_shift");
  // degenerate_gap keeps its default: no key sets it (it splits far below any mesh asymmetry).
  // SLEPc 3.18's spectrum slicing refuses fewer than 10 eigenpairs per shift (EPSSetUp), which
  // would fail every task after the sweep started.
  if (solve.nev_per_shift != 0 && solve.nev_per_shift < 10)
    throw InputError(fmt::format("solver.nev_per_shift = {}: spectrum slicing needs 0 (SLEPc's default) or at least 10",
                                 solve.nev_per_shift));
  if (!(solve.residual_limit > solve.tolerance))
    throw InputError(fmt::format("solver.residual_limit = {} must exceed solver.tolerance = {}: the solver stops at "
                                 "its tolerance", solve.residual_limit, solve.tolerance));
  return solve;
}

void read_transfer_keys(const io::Config& config, model::TransferSettings& transfer) {
  transfer.sound_speed_m_s = config.real("medium.c_m_s");
  transfer.air_density_kg_m3 = config.real("medium.rho_kg_m3");
  transfer.sources_per_wavelength = config.real("transfer.sources_per_wavelength");
  transfer.residual_target = config.real("transfer.residual_target");
  transfer.tail_tolerance = config.real("transfer.tail_tolerance");
}

kernels::fem::EllipsoidMeshBounds mesh_bounds(const io::Config& config) {
  return {config.real("mesh.max_radius_edge"), config.real("mesh.min_dihedral_deg"), config.real("mesh.min_jacobian_ratio")};
}

ModalSpec make_modal_spec(const io::Config& config) {
  ModalSpec spec;
  auto& h = spec.header;
  h.material = io::find_material(io::read_materials(config.string("material.table"), spec.material_table),
                                 config.string("material.name"), spec.material_table);
  // The damping is optional in the table (grounds have none), but a modal bank's modes need it.
  if (!h.material.damping)
    throw InputError(fmt::format("{}: [{}]: missing key 'rayleigh_alpha_1_s' (and 'rayleigh_beta_s'): a modal bank needs the "
                                 "material's Rayleigh damping",
                                 spec.material_table, h.material.name));
  h.min_ratio = config.real("patch.min_ratio");
  // The cigar's b/c is its a/c: below min_ratio it would leave the patch's a/c >= min_ratio.
  h.cigar_ratio = std::max(config.real("patch.cigar_ratio"), h.min_ratio);
  h.solve = solve_settings(config);
  h.solve.f_max_multiple = config.real("modes.f_max_multiple");
  h.band = {config.real("modes.top_hz"), config.real("modes.largest_piece_m"), config.real("modes.proxy_above_hz"),
            config.real("modes.max_multiple")};
  if (h.band.max_multiple < h.solve.f_max_multiple)
    throw InputError(fmt::format("modes.max_multiple = {} is below modes.f_max_multiple = {}: the band's limit must "
                                 "allow its smallest multiple", h.band.max_multiple, h.solve.f_max_multiple));
  h.elements_per_wavelength = config.real("mesh.elements_per_wavelength");
  h.coarse_edge_m = config.real("mesh.coarse_edge_m");
  h.elements_through_thickness = config.real("mesh.elements_through_thickness");
  h.coarse_elements_through_thickness = config.real("mesh.coarse_elements_through_thickness");
  h.layered_below_ratio = config.real("mesh.layered_below_ratio");
  h.layers = static_cast<std::int32_t>(config.integer("mesh.layers"));
  h.coarse_layers = static_cast<std::int32_t>(config.integer("mesh.coarse_layers"));
  h.transfer.method = "equivalent sources (monopoles on a layer under the surface, 8 parity classes), multipole "
                      "about the centre";
  read_transfer_keys(config, h.transfer);
  h.transfer.points_per_source = config.real("transfer.points_per_source");
  spec.bounds = mesh_bounds(config);
  const auto& list = config.reals("patch.samples");
  if (list.empty()) throw InputError("patch.samples = []: a modal bank needs at least one ellipsoid");
  if (list.size() / 3 > kMaxSamples)
    throw InputError(fmt::format("patch.samples: {} ellipsoids; at most {}", list.size() / 3, kMaxSamples));
  for (std::size_t i = 0; i + 2 < list.size(); i += 3) {
    const std::array<double, 3> axes{list[i], list[i + 1], list[i + 2]};
    const std::string why = kernels::modal::patch_violation(axes, {h.min_ratio, h.cigar_ratio}, 1e-6);
    if (!why.empty())
      throw InputError(fmt::format("patch.samples[{}] = [{}, {}, {}]: {} (patch.min_ratio = {}, patch.cigar_ratio = {})",
                                   i / 3, axes[0], axes[1], axes[2], why, h.min_ratio, h.cigar_ratio));
    const double norm = std::sqrt(axes[0] * axes[0] + axes[1] * axes[1] + axes[2] * axes[2]);
    spec.samples_m.push_back({axes[0] / norm, axes[1] / norm, axes[2] / norm});  // to rounding
    for (std::size_t j = 0; j + 1 < spec.samples_m.size(); ++j)
      if (spec.samples_m[j] == spec.samples_m.back())
        throw InputError(fmt::format("patch.samples[{}] = [{}, {}, {}]: the same ellipsoid as patch.samples[{}]", i / 3,
                                     axes[0], axes[1], axes[2], j));
  }
  return spec;
}

std::string modal_sweep_toml(const io::Config& config, const ModalSpec& spec) {
  const auto& m = spec.header.material;
  // The built-in table named as banks before the one materials table named it: the text is hashed
  // into the sweep id, and a bank at OUT of another sweep id is only replaced with --force.
  const std::string table = config.string("material.table").empty() ? "built-in configs/materials.toml"
                                                                     : spec.material_table;
  return config.to_toml() +
         fmt::format("\n# material '{}' as read from {}:\n# rho_kg_m3 = {:.17g}, youngs_pa = {:.17g}, poisson = {:.17g}, "
                     "rayleigh_alpha_1_s = {:.17g}, rayleigh_beta_s = {:.17g}\n",
                     m.name, table, m.rho_kg_m3, m.youngs_pa, m.poisson, m.damping.value().alpha_1_s,
                     m.damping.value().beta_s);
}

std::string band_text(const model::ModalBankHeader& h) {
  const auto& b = h.band;
  if (b.largest_piece_m <= 0) return fmt::format("modes to {:g} f_1", h.solve.f_max_multiple);
  const std::string proxy = b.proxy_above_hz > 0 ? fmt::format(", at most {:g} Hz / {:g} Hz", b.top_hz, b.proxy_above_hz) : "";
  return fmt::format("modes to k f_1, k = {:g} Hz x {:g} m / (2 c f_1){} within [{:g}, {:g}]: every piece up to {:g} m "
                     "long{} gets every mode to {:g} Hz", b.top_hz, b.largest_piece_m, proxy, h.solve.f_max_multiple,
                     b.max_multiple, b.largest_piece_m,
                     b.proxy_above_hz > 0 ? fmt::format(" whose f_0 is at least {:g} Hz", b.proxy_above_hz) : "", b.top_hz);
}

std::vector<ModalTask> modal_tasks(const ModalSpec& spec) {
  std::vector<ModalTask> tasks;
  for (std::size_t i = 0; i < spec.samples_m.size(); ++i) tasks.push_back({i, fmt::format("e{:03d}", i)});
  return tasks;
}

}  // namespace clatter::jobs
