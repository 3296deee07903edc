#include "banks/modal/modal_job.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "io/modal_bank.hpp"
#include "io/sweep_files.hpp"
#include "banks/modal/modal_fem.hpp"
#include "banks/modal/modal_solve.hpp"
#include "banks/modal/modal_transfer.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {
namespace {

using clock_type = std::chrono::steady_clock;
double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

double since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }

// Every rank meshes alike (TetGen is deterministic), so a failure is the same everywhere.
kernels::fem::EllipsoidMesh mesh_or_fail(const ModalSpec& spec, const std::array<double, 3>& axes, double h_m,
                                         double elements_through_thickness, MeshFor purpose = MeshFor::entry) {
  Stage stage("mesh");
  try {
    return mesh_entry(spec, axes, h_m, elements_through_thickness, purpose);
  } catch (const std::exception& e) {
    throw TaskFailure(e.what());
  }
}

// The multiplets by symmetry from the surface shapes (kernels/modal/multiplets.hpp).
void store_multiplets(const kernels::modal::EllipsoidSymmetry& symmetry, model::ModalEntry& entry) {
  const auto m = kernels::modal::find_multiplets(entry.surface_nodes_m, entry.surface_faces, entry.shapes, entry.cluster,
                                                 symmetry);
  entry.multiplet = m.multiplet;
  entry.symmetry_order = m.order;
  using kernels::modal::SymmetryKind;
  entry.symmetry = {symmetry.kind == SymmetryKind::sphere ? "sphere" : symmetry.kind == SymmetryKind::spheroid ? "spheroid" : "none",
                    symmetry.axis, m.order_defect, m.incomplete};
  if (m.incomplete > 0 || m.order_defect > 0.25)
    spdlog::warn("modal: {} multiplet(s) incomplete, orders within {:.2f} of integers: a cluster is not a whole "
                 "symmetric subspace", m.incomplete, m.order_defect);
}

}  // namespace

model::ModalMeshStats mesh_stats(const kernels::fem::MeshQuality& q) {
  return {q.elements,         q.nodes,           q.dofs,         q.edge_length_m, q.max_radius_edge,
          q.mean_radius_edge, q.min_dihedral_deg, q.max_dihedral_deg, q.min_jacobian_ratio};
}

void store_modes(MPI_Comm group, const ModeSet& modes, const kernels::fem::Tet10Mesh& mesh,
                 const std::vector<kernels::fem::BoundaryFace>& boundary, const model::Material& material,
                 const kernels::modal::EllipsoidSymmetry& symmetry, model::ModalEntry& entry) {
  Stage stage("surface");
  // The surface nodes (in ascending mesh order) and the faces renumbered onto them.
  std::map<int, std::int32_t> index;
  for (const auto& face : boundary)
    for (int v : face) index.emplace(v, 0);
  std::vector<int> surface;
  for (auto& [node, at] : index) {
    at = static_cast<std::int32_t>(surface.size());
    surface.push_back(node);
    const auto p = mesh.nodes_m.col(node);
    entry.surface_nodes_m.push_back({p(0), p(1), p(2)});
  }
  for (const auto& face : boundary) {
    std::array<std::int32_t, 6> f{};
    for (int k = 0; k < 6; ++k) f[static_cast<std::size_t>(k)] = index.at(face[static_cast<std::size_t>(k)]);
    entry.surface_faces.push_back(f);
  }
  const bool root = mpi::rank(group) == 0;
  for (std::size_t i = 0; i < modes.lambdas.size(); ++i) {
    const std::vector<double> u = modes.vectors[i].gather_to_root();
    if (!root) continue;
    for (int node : surface)
      for (int c = 0; c < 3; ++c) entry.shapes.push_back(u[static_cast<std::size_t>(3 * node + c)]);
    const double omega = std::sqrt(modes.lambdas[i]);
    entry.frequencies_hz.push_back(omega / (2 * std::numbers::pi));
    entry.damping_ratios.push_back(material.damping_ratio(omega));
    entry.cluster.push_back(modes.cluster[i]);
    entry.relative_residuals.push_back(modes.relative_residuals[i]);
  }
  entry.band = modes.band;
  if (root) store_multiplets(symmetry, entry);
}

bool layered_entry(const model::ModalBankHeader& header, const std::array<double, 3>& axes) {
  return axes[0] < header.layered_below_ratio * axes[1];
}

double layered_edge_length_m(const model::ModalBankHeader& header, const std::array<double, 3>& axes, double h_m) {
  // The frequency h_m resolves (modal_edge_length_m inverted), and the Kirchhoff bending
  // wavelength there of a plate as thick as the entry's middle, T = 2a:
  // lambda_b = 2 pi (D / (rho T))^(1/4) / sqrt(omega), D / (rho T) = c_p^2 T^2 / 12.
  const auto& m = header.material;
  const double f_hz = m.shear_speed_m_s() / (h_m * header.elements_per_wavelength);
  const double plate_speed_m_s = std::sqrt(m.youngs_pa / (m.rho_kg_m3 * (1 - m.poisson * m.poisson)));
  const double bending_wavelength_m = std::sqrt(2 * std::numbers::pi * plate_speed_m_s * 2 * axes[0] / (std::sqrt(12.0) * f_hz));
  return std::min(h_m, bending_wavelength_m / (kBendingOverShear * header.elements_per_wavelength));
}

kernels::fem::EllipsoidMesh mesh_entry(const ModalSpec& spec, const std::array<double, 3>& axes, double h_m,
                                       double elements_through_thickness, MeshFor purpose) {
  std::string reasons;
  const bool layered = layered_entry(spec.header, axes);
  for (double factor : {1.0, 0.7, 0.5}) {
    try {
      if (layered) {
        kernels::fem::LayeredMeshSettings settings;
        settings.semi_axes_m = axes;
        settings.edge_length_m = factor * (purpose == MeshFor::entry ? layered_edge_length_m(spec.header, axes, h_m) : h_m);
        settings.layers = purpose == MeshFor::entry ? spec.header.layers : spec.header.coarse_layers;
        return kernels::fem::mesh_layered_ellipsoid(settings, spec.bounds);
      }
      kernels::fem::EllipsoidMeshSettings settings{axes, factor * h_m};
      settings.elements_through_thickness = elements_through_thickness / factor;  // the cap may fix h
      settings.spacing_per_curvature_radius *= factor;
      return kernels::fem::mesh_ellipsoid(settings, spec.bounds);
    } catch (const kernels::fem::MeshError& e) {
      reasons += fmt::format("{}at h = {:.4g} m: {}", reasons.empty() ? "" : "; ", factor * h_m, e.what());
    }
  }
  throw kernels::fem::MeshError(fmt::format("no mesh within the quality bounds ({})", reasons));
}

double entry_band_multiple(const ModalSpec& spec, const std::array<double, 3>& axes, double f1_hz) {
  return model::band_multiple(spec.header.band, spec.header.solve.f_max_multiple, axes[2], f1_hz);
}

double modal_edge_length_m(const ModalSpec& spec, double f_max_hz) {
  return spec.header.material.shear_speed_m_s() / f_max_hz / spec.header.elements_per_wavelength;
}

FirstModeEstimate estimate_first_mode(MPI_Comm comm, const ModalSpec& spec, const std::array<double, 3>& axes) {
  Stage stage("estimate");
  const auto& material = spec.header.material;
  auto coarse = mesh_or_fail(spec, axes, spec.header.coarse_edge_m, spec.header.coarse_elements_through_thickness,
                             MeshFor::estimate);
  FemModel model = assemble_fem(comm, coarse.mesh, material);
  // A sphere of radius c rings at omega c / c_s ~ 2.5 (Lamb's n = 2); a plate's or a rod's first
  // mode bends, at omega ~ c_s x thickness / length^2: a / c times the sphere's.
  const double guess = std::pow(2.5 * material.shear_speed_m_s() * axes[0] / (axes[2] * axes[2]), 2);
  const double lambda1 = first_elastic_lambda(model, guess, spec.header.solve);
  return {std::move(coarse), std::move(model), lambda1};
}

model::ModalEntry build_modal_entry(MPI_Comm group, const ModalSpec& spec, std::size_t index) {
  const auto t_start = clock_type::now();
  const auto& axes = spec.samples_m.at(index);
  const auto& material = spec.header.material;
  model::ModalEntry entry;
  entry.cost.ranks = mpi::size(group);
  double lambda1_estimate = 0;
  {  // a block: the coarse model is freed before the fine one is assembled
    const auto t0 = clock_type::now();
    lambda1_estimate = estimate_first_mode(group, spec, axes).lambda1;
    entry.cost.estimate_s = since(t0);
  }
  const double f1_estimate_hz = frequency_hz(lambda1_estimate);
  model::ModalSolveSettings settings = spec.header.solve;
  settings.f_max_multiple = entry_band_multiple(spec, axes, f1_estimate_hz);
  auto t0 = clock_type::now();
  const double h_m = modal_edge_length_m(spec, settings.f_max_multiple * f1_estimate_hz);
  const auto mesh = mesh_or_fail(spec, axes, h_m, spec.header.elements_through_thickness);
  entry.cost.mesh_s = since(t0);
  t0 = clock_type::now();
  std::optional<FemModel> model;
  {
    Stage stage("assembly");
    model.emplace(assemble_fem(group, mesh.mesh, material));
  }
  const auto reference = reference_fields(model->layout, mesh.mesh, axes);
  entry.cost.assembly_s = since(t0);
  ModeSet modes;
  {
    Stage stage("eigensolve");
    t0 = clock_type::now();
    modes = solve_modes(*model, reference, lambda1_estimate, settings, {h_m, material.shear_speed_m_s()});
    entry.cost.solve_s = since(t0);
  }
  entry.cost.factor_memory_mb = static_cast<double>(modes.stats.check_factor.memory_max_mb);
  entry.cost.memory_max_mb = modes.stats.memory_max_mb;
  entry.sample = static_cast<std::uint32_t>(index);
  entry.axes_m = axes;
  entry.mesh = mesh_stats(mesh.quality);
  entry.solve = modes.record;
  entry.solve.first_mode_estimate_hz = f1_estimate_hz;
  store_modes(group, modes, mesh.mesh, mesh.boundary, material, kernels::modal::ellipsoid_symmetry(axes), entry);
  const auto& transfer = spec.header.transfer;
  compute_modal_transfer(group, [&transfer](const model::ModalEntry& e, std::size_t mode) { return mode_transfer(e, mode, transfer); },
                         entry);
  entry.cost.total_s = since(t_start);
  if (mpi::rank(group) != 0) return {};
  return entry;
}

TaskWriter run_modal_task(MPI_Comm group, const ModalSpec& spec, const ModalTask& task) {
  auto entry = build_modal_entry(group, spec, task.entry);
  if (mpi::rank(group) != 0) return {};
  spdlog::info("modal: {} axes ({:.4f}, {:.4f}, {:.4f}): {} modes {:.1f}-{:.1f} Hz, {} dofs; transfer {:.1f} s, "
               "median boundary residual {:.1e}; {:.1f} s", task.name, entry.axes_m[0], entry.axes_m[1], entry.axes_m[2],
               entry.modes(), entry.frequencies_hz.front(), entry.frequencies_hz.back(), entry.mesh.dofs,
               entry.cost.transfer_s, median(entry.transfer.boundary_residual), entry.cost.total_s);
  // The bank's promise (docs/transfer.md): residuals within 2 % wherever a mode moves its surface
  // along the normal by more than 0.3 of its motion. A mode that misses it radiates an unknown
  // field: said here, not only in `info`.
  std::string missed;
  int missed_count = 0;
  for (std::size_t m = 0; m < entry.modes(); ++m)
    if (entry.transfer.normal_fraction[m] > model::kNormalFractionPromised &&
        entry.transfer.boundary_residual[m] > model::kResidualPromised) {
      ++missed_count;
      if (missed_count <= 8) missed += fmt::format(" {} ({:.1f} Hz: {:.2e})", m, entry.frequencies_hz[m], entry.transfer.boundary_residual[m]);
    }
  if (missed_count > 0)
    spdlog::warn("modal: {}: the transfer of {} of {} modes misses the promised boundary residual {:g} (mode, frequency, residual):{}{}",
                 task.name, missed_count, entry.modes(), model::kResidualPromised, missed, missed_count > 8 ? " ..." : "");
  return [entry = std::move(entry)](io::File& file, const std::string& group_name) {
    io::write_modal_entry(file, group_name, entry);
  };
}

model::ModalBank merge_modal_results(const ModalSpec& spec, const std::string& results_dir,
                                     const std::string& config_toml) {
  model::ModalBank bank;
  bank.header = spec.header;
  const auto tasks = modal_tasks(spec);
  bank.sweep.sweep_id = io::sweep_id(config_toml);
  bank.sweep.tasks_total = static_cast<std::uint32_t>(tasks.size());
  for (const auto& t : tasks) {
    const auto& a = spec.samples_m[t.entry];
    const std::string label = fmt::format("{} axes ({:.4f}, {:.4f}, {:.4f}) m", t.name, a[0], a[1], a[2]);
    if (!task_done(results_dir, t.name, label, config_toml, bank.sweep)) continue;
    const std::string path = io::task_path(results_dir, t.name);
    auto file = io::File::open(path);
    auto entry = io::read_modal_entry(file, "/result");
    if (entry.axes_m != a || entry.sample != t.entry)
      throw InputError(fmt::format("{}: holds axes ({}, {}, {}), the sweep's task {} has ({}, {}, {})", path,
                                   entry.axes_m[0], entry.axes_m[1], entry.axes_m[2], t.name, a[0], a[1], a[2]));
    bank.entries.push_back(std::move(entry));
  }
  for (const auto& e : bank.entries)
    bank.header.ranks_per_task = (&e == &bank.entries.front() || e.cost.ranks == bank.header.ranks_per_task) ? e.cost.ranks : 0;
  return bank;
}

}  // namespace clatter::jobs
