#include "banks/modal/object_job.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>

#include "banks/modal/modal_fem.hpp"
#include "banks/modal/modal_job.hpp"
#include "banks/modal/modal_solve.hpp"
#include "banks/modal/modal_transfer.hpp"
#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "io/object_bank.hpp"
#include "io/sweep_files.hpp"
#include "kernels/fem/object_mesh.hpp"
#include "kernels/mass_properties.hpp"
#include "kernels/transfer/mesh_transfer.hpp"
#include "kernels/transfer/multipole.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {
namespace {

using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0) { return std::chrono::duration<double>(clock_type::now() - t0).count(); }

namespace kt = kernels::transfer;

// One mode's transfer for the entry's own surface (kernels/transfer/mesh_transfer.hpp), in the
// record the modal kind's transfer stage gathers.
kt::ModeTransfer object_mode_transfer(const model::ModalEntry& e, std::size_t mode, const model::TransferSettings& s) {
  const std::size_t per_mode = 3 * e.surface_nodes_m.size();
  const std::span<const double> shape(e.shapes.data() + mode * per_mode, per_mode);
  const auto t = kt::solve_mesh_mode_transfer(e.surface_nodes_m, e.surface_faces, shape,
                                              2 * std::numbers::pi * e.frequencies_hz[mode], s);
  kt::ModeTransfer out;
  out.expansion = t.expansion;
  out.boundary_residual = t.boundary_residual;
  out.normal_fraction = t.normal_fraction;
  out.amplification = t.amplification;
  out.source_depth = t.source_depth_m;  // metres here: an object has no semi-axis a to scale by
  out.attempts = t.attempts;
  out.sources = t.sources + t.dipoles;
  out.fit_points = t.fit_points;
  return out;
}

}  // namespace

double object_edge_length_m(const ObjectSpec& spec, const model::Material& material) {
  return material.shear_speed_m_s() / spec.header.f_max_hz / spec.header.elements_per_wavelength;
}

model::ObjectEntry build_object_entry(MPI_Comm group, const ObjectSpec& spec, std::size_t index, bool with_transfer) {
  const auto t_start = clock_type::now();
  const ObjectSource& o = spec.objects.at(index);
  const model::Material& material = o.material;
  model::ObjectEntry e;
  e.key = o.key();
  e.mesh_hash = o.mesh_hash;
  e.source = o.mesh_path;
  e.material = material;
  model::ModalEntry& entry = e.modal;
  entry.cost.ranks = mpi::size(group);
  entry.sample = static_cast<std::uint32_t>(index);
  // The body frame of a scene object given by this mesh: its axes, about its centre of mass.
  const auto props = kernels::mesh_mass_properties(o.mesh.vertices_m, o.mesh.triangles);
  e.centre_m = props.centroid_m;
  e.volume_m3 = props.volume_m3;
  e.mass_kg = material.rho_kg_m3 * props.volume_m3;
  e.surface_area_m2 = props.surface_area_m2;
  std::vector<std::array<double, 3>> body = o.mesh.vertices_m;
  std::array<double, 3> half_extent{};
  for (auto& v : body)
    for (int c = 0; c < 3; ++c) {
      v[c] -= e.centre_m[c];
      half_extent[c] = std::max(half_extent[c], std::abs(v[c]));
    }
  entry.axes_m = half_extent;

  auto t0 = clock_type::now();
  const double h_m = object_edge_length_m(spec, material);
  kernels::fem::ObjectMesh mesh;
  {
    Stage stage("mesh");
    try {
      mesh = kernels::fem::mesh_object(body, o.mesh.triangles,
                                       {h_m, static_cast<int>(spec.header.elements_through_thickness)}, spec.bounds);
    } catch (const std::exception& err) {
      throw TaskFailure(fmt::format("{}: {}", o.mesh_path, err.what()));
    }
  }
  e.min_thickness_m = mesh.min_thickness_m;
  e.curved_edges = mesh.curved_edges;
  entry.cost.mesh_s = since(t0);
  t0 = clock_type::now();
  std::optional<FemModel> model;
  {
    Stage stage("assembly");
    model.emplace(assemble_fem(group, mesh.mesh, material));
  }
  const auto reference = reference_fields(model->layout, mesh.mesh, half_extent);
  entry.cost.assembly_s = since(t0);
  ModeSet modes;
  double f1_hz = 0;
  {
    Stage stage("eigensolve");
    t0 = clock_type::now();
    double radius_m = 0;
    for (const auto& v : body) radius_m = std::max(radius_m, std::hypot(v[0], v[1], v[2]));
    // A sphere of radius R rings at omega R / c_s ~ 2.5 (Lamb's n = 2); a plate or bar far lower:
    // the inertia bracketing finds f_1 from either side.
    const double guess = std::pow(2.5 * material.shear_speed_m_s() / radius_m, 2);
    const double lambda1 = first_elastic_lambda(*model, guess, spec.header.solve);
    f1_hz = frequency_hz(lambda1);
    entry.cost.estimate_s = since(t0);
    model::ModalSolveSettings settings = spec.header.solve;
    // The band is absolute; an object whose first mode lies above f_max keeps its first multiplet.
    settings.f_max_multiple = std::max(1.0, spec.header.f_max_hz / f1_hz);
    // The band's margin from the shear-wavelength edge h_m (the thickness cap only refines).
    modes = solve_modes(*model, reference, lambda1, settings, {h_m, material.shear_speed_m_s()});
    entry.cost.solve_s = since(t0);
  }
  entry.cost.factor_memory_mb = static_cast<double>(modes.stats.check_factor.memory_max_mb);
  entry.cost.memory_max_mb = modes.stats.memory_max_mb;
  entry.mesh = mesh_stats(mesh.quality);
  entry.solve = modes.record;
  entry.solve.first_mode_estimate_hz = f1_hz;
  model.reset();
  store_modes(group, modes, mesh.mesh, mesh.boundary, material, {}, entry);  // an arbitrary mesh: no symmetry
  for (const auto& x : entry.surface_nodes_m) e.radius_m = std::max(e.radius_m, std::hypot(x[0], x[1], x[2]));
  const auto& transfer = spec.header.transfer;
  if (with_transfer)
    compute_modal_transfer(
        group, [&transfer](const model::ModalEntry& m, std::size_t mode) { return object_mode_transfer(m, mode, transfer); },
        entry);
  entry.cost.total_s = since(t_start);
  if (mpi::rank(group) != 0) return {};
  return e;
}

TaskWriter run_object_task(MPI_Comm group, const ObjectSpec& spec, const ObjectTask& task) {
  auto e = build_object_entry(group, spec, task.object);
  if (mpi::rank(group) != 0) return {};
  const auto& m = e.modal;
  std::vector<double> residuals = m.transfer.boundary_residual;
  std::sort(residuals.begin(), residuals.end());
  spdlog::info("object: {} ({}): {} modes {:.1f}-{:.1f} Hz, {} dofs (h {:.3g} m, thinnest {:.3g} m); transfer {:.1f} s, "
               "median boundary residual {:.1e}; {:.1f} s",
               task.name, e.source, m.modes(), m.frequencies_hz.empty() ? 0.0 : m.frequencies_hz.front(),
               m.frequencies_hz.empty() ? 0.0 : m.frequencies_hz.back(), m.mesh.dofs, m.mesh.edge_length_m,
               e.min_thickness_m, m.cost.transfer_s, residuals.empty() ? 0.0 : residuals[residuals.size() / 2],
               m.cost.total_s);
  return [e = std::move(e)](io::File& file, const std::string& group_name) { io::write_object_entry(file, group_name, e); };
}

model::ObjectBank merge_object_results(const ObjectSpec& spec, const std::string& results_dir,
                                       const std::string& config_toml) {
  model::ObjectBank bank;
  bank.header = spec.header;
  const auto tasks = object_tasks(spec);
  bank.sweep.sweep_id = io::sweep_id(config_toml);
  bank.sweep.tasks_total = static_cast<std::uint32_t>(tasks.size());
  for (const auto& t : tasks) {
    const std::string label = fmt::format("{} ({})", t.name, spec.objects[t.object].mesh_path);
    if (!task_done(results_dir, t.name, label, config_toml, bank.sweep)) continue;
    const std::string path = io::task_path(results_dir, t.name);
    auto file = io::File::open(path);
    auto entry = io::read_object_entry(file, "/result");
    if (entry.key != t.name)
      throw InputError(fmt::format("{}: holds entry '{}', the sweep's task is '{}'", path, entry.key, t.name));
    bank.entries.push_back(std::move(entry));
  }
  for (const auto& e : bank.entries)
    bank.header.ranks_per_task =
        (&e == &bank.entries.front() || e.modal.cost.ranks == bank.header.ranks_per_task) ? e.modal.cost.ranks : 0;
  return bank;
}

}  // namespace clatter::jobs
