#include "banks/modal/modal_plan.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "core/errors.hpp"
#include "banks/modal/modal_job.hpp"
#include "banks/modal/modal_spec.hpp"
#include "cli/run_options.hpp"
#include "kernels/transfer/mode_transfer.hpp"
#include "kernels/transfer/surface_interpolation.hpp"
#include "petsc/inertia.hpp"

namespace clatter::jobs {
namespace {

// The eigen-solve ~ dofs^1.05 (1 + modes / 2.8): a fixed share (the slice's end factorizations and
// the count check) and one per mode (shifts and solves with the factors). Fitted, with the
// transfer's constants below, to the 77 entries of the default bank (2026-12-05, 2 358 to 125 199
// dofs, 11 to 65 modes; docs/benchmarks.md "The default bank of 77 entries") anchored on its
// smallest entry as `plan` is: 63 of 77 within 30 %, the whole bank within 4 %. (The former
// 1.34 and 18 came from 5 entries and over-predicted this bank 1.6x.) The pre-solve (one
// factorization and a few Krylov restarts on the coarse mesh) grows like its dofs; mesh and
// assembly like the entry's.
constexpr double kDofsExponent = 1.05;
constexpr double kModesPerFixedShare = 2.8;
constexpr double kEstimateExponent = 1.0;
// Factor memory of 3-D nested dissection grows like n^(4/3).
constexpr double kMemoryExponent = 4.0 / 3.0;
// Measured (docs/benchmarks.md "Modal bank"): 2 ranks per task run the default sphere entry 1.23x
// faster than 1 (the slicing's triangular solves scale poorly), 2^0.3 = 1.23.
constexpr double kGroupSpeedupExponent = 0.3;
// The transfer's time per mode is a fixed part (the surface data, the multipole expansion) plus one
// that scales with the work of its layouts' fits (kernels/transfer layout_size: the QR's fit points
// x unknowns^2 and the Green's functions of the fill and the check, set by the air wavelength, the
// mesh's spacing and the shape's layout) to the power 1.11, the fixed part worth work^1.11 = 5e8;
// the work is averaged over the entry's modes, whose density grows like f^2 on a bulky entry
// (Weyl) and like f on a flat one (a plate's); spread evenly over a group. Fitted with the FEM's
// constants above (the former work^0.8 alone left the thin entries' share 2x off).
constexpr double kTransferWorkExponent = 1.11;
constexpr double kTransferFixedWork = 5e8;
double transfer_work(const ModalSpec& spec, const std::array<double, 3>& axes, double f1_hz, double f_max_hz,
                     const kernels::fem::EllipsoidMesh& mesh) {
  std::vector<std::array<double, 3>> nodes;
  for (Eigen::Index v = 0; v < mesh.mesh.nodes_m.cols(); ++v)
    nodes.push_back({mesh.mesh.nodes_m(0, v), mesh.mesh.nodes_m(1, v), mesh.mesh.nodes_m(2, v)});
  std::vector<std::array<std::int32_t, 6>> faces;
  for (const auto& f : mesh.boundary) faces.push_back({f[0], f[1], f[2], f[3], f[4], f[5]});
  const double spacing_m = kernels::transfer::surface_node_spacing_m(nodes, faces);
  const double density_power = layered_entry(spec.header, axes) ? 1 : 2;
  double work = 0, weight = 0;
  constexpr int kSamples = 8;
  for (int i = 0; i < kSamples; ++i) {
    const double f = f1_hz + (f_max_hz - f1_hz) * (i + 0.5) / kSamples, w = std::pow(f, density_power);
    work += w * kernels::transfer::layout_size(axes, 2 * std::numbers::pi * f, spacing_m, spec.header.transfer).work;
    weight += w;
  }
  return work / weight;
}

struct EntryPlan {
  double f1_hz = 0, k = 0, h_m = 0;
  double transfer_work = 0;  // per mode (transfer_work above)
  long long dofs = 0, coarse_dofs = 0, modes = 0;
  double task_s = 0, memory_mb = 0;
  std::string failure;  // the mesh or pre-solve failed: the task will fail the same way
};

EntryPlan plan_entry(const ModalSpec& spec, std::size_t i) {
  EntryPlan p;
  const auto& axes = spec.samples_m[i];
  try {
    const FirstModeEstimate coarse = estimate_first_mode(MPI_COMM_SELF, spec, axes);  // the job's own
    p.f1_hz = coarse.f1_hz();
    p.k = entry_band_multiple(spec, axes, p.f1_hz);
    p.modes = petsc::eigenvalues_below(coarse.model.K, coarse.model.M, p.k * p.k * coarse.lambda1 * 1.0001) - 6;
    p.coarse_dofs = coarse.mesh.quality.dofs;
    p.h_m = modal_edge_length_m(spec, p.k * p.f1_hz);
    const auto mesh = mesh_entry(spec, axes, p.h_m, spec.header.elements_through_thickness);
    p.dofs = mesh.quality.dofs;
    p.transfer_work = transfer_work(spec, axes, p.f1_hz, p.k * p.f1_hz, mesh);
  } catch (const std::exception& e) {
    p.failure = e.what();
  }
  return p;
}

}  // namespace

PlanEstimate modal_plan_estimate(const io::Config& config, const PlanOptions& o) {
  const ModalSpec spec = make_modal_spec(config);
  const auto tasks = modal_tasks(spec);
  std::vector<EntryPlan> entries;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < tasks.size(); ++i) entries.push_back(plan_entry(spec, i));
  const double presolve_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // Calibration: the smallest entry that meshes, solved in full as the sweep will.
  std::size_t cal = tasks.size();
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (entries[i].failure.empty() && (cal == tasks.size() || entries[i].dofs < entries[cal].dofs)) cal = i;
  if (cal == tasks.size()) throw InputError("plan: no entry of the sweep meshes; see mesh.* and patch.samples");
  const auto entry = build_modal_entry(MPI_COMM_SELF, spec, cal);
  const double cal_transfer_s = entry.cost.transfer_s, cal_estimate_s = entry.cost.estimate_s,
               cal_setup_s = entry.cost.mesh_s + entry.cost.assembly_s,
               cal_solve_s = entry.cost.total_s - cal_transfer_s - cal_estimate_s - cal_setup_s;
  const double cal_modes = static_cast<double>(std::max<std::size_t>(entry.modes(), 1));
  // The coarse mesh undercounts the top of the range (its frequencies are high): scaled by what
  // the calibration entry's fine solve found against its coarse count.
  const double count_scale = cal_modes / static_cast<double>(std::max<long long>(entries[cal].modes, 1));
  // MUMPS' own figure: the process's resident size here also holds every pre-solve before it.
  const double cal_dofs = static_cast<double>(entry.mesh.dofs), cal_memory = entry.cost.factor_memory_mb;
  const double group_speedup = std::pow(o.ranks_per_task, kGroupSpeedupExponent);
  PlanEstimate e;
  double core_s = 0, worst_memory = 0;
  for (auto& p : entries) {
    if (!p.failure.empty()) {
      e.task_s.push_back(0);
      continue;
    }
    p.modes = std::llround(static_cast<double>(p.modes) * count_scale);
    const double dofs_ratio = static_cast<double>(p.dofs) / cal_dofs;
    const double mode_ratio = static_cast<double>(p.modes) / cal_modes;
    const double coarse_ratio = static_cast<double>(p.coarse_dofs) / static_cast<double>(entries[cal].coarse_dofs);
    const double fem_s = cal_estimate_s * std::pow(coarse_ratio, kEstimateExponent) + cal_setup_s * dofs_ratio +
                         cal_solve_s * std::pow(dofs_ratio, kDofsExponent) * (1 + static_cast<double>(p.modes) / kModesPerFixedShare) /
                             (1 + cal_modes / kModesPerFixedShare);
    const double work_share = (kTransferFixedWork + std::pow(p.transfer_work, kTransferWorkExponent)) /
                              (kTransferFixedWork + std::pow(entries[cal].transfer_work, kTransferWorkExponent));
    p.task_s = fem_s / group_speedup + cal_transfer_s * mode_ratio * work_share / o.ranks_per_task;
    p.memory_mb = cal_memory * std::pow(dofs_ratio, kMemoryExponent) / o.ranks_per_task;
    e.task_s.push_back(p.task_s);
    core_s += p.task_s * o.ranks_per_task;
    worst_memory = std::max(worst_memory, p.memory_mb);
  }
  const int cores = o.cores_per_node > 0 ? o.cores_per_node : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  e.nodes = (o.ranks + cores - 1) / cores;
  const int groups = o.ranks / o.ranks_per_task;
  const double wall_s = list_schedule_s(e.task_s, groups);
  e.signal_lead_s = static_cast<int>(std::max(120.0, 1.2 * *std::max_element(e.task_s.begin(), e.task_s.end()) + 60));
  const auto& m = spec.header.material;
  e.report = fmt::format("plan: {}: modal bank of {} ellipsoids, {} (c_s = {:.1f} m/s), {}\n",
                         o.config_path.empty() ? "defaults" : o.config_path, tasks.size(), m.name, m.shear_speed_m_s(),
                         band_text(spec.header));
  e.report += fmt::format("  pre-solves:  every entry's f_1, h, dofs and mode count (coarse inertia) in {:.1f} s here\n",
                          presolve_s);
  e.report += fmt::format("  calibration: {} solved here in {:.1f} s + {:.1f} s transfer: {} modes, {} dofs, {:.0f} MB MUMPS "
                          "factors; time ~ (coarse dofs^{} + dofs + dofs^{} (1 + modes/{})) / ranks_per_task^{} + "
                          "modes x ({:.0e} + (its layouts' work: QR and Green's functions)^{}) / ranks_per_task\n",
                          tasks[cal].name, entry.cost.total_s - cal_transfer_s, cal_transfer_s, entry.modes(),
                          entry.mesh.dofs, cal_memory, kEstimateExponent, kDofsExponent, kModesPerFixedShare,
                          kGroupSpeedupExponent, kTransferFixedWork, kTransferWorkExponent);
  e.report += fmt::format("  job:         {} ranks on {} node(s) of {} cores, {} group(s) of {}: {:.2f} core-hours\n",
                          o.ranks, e.nodes, cores, groups, o.ranks_per_task, core_s / 3600);
  e.report += fmt::format("  predicted:   {} wall (tasks handed out in order); largest MUMPS factors per rank ~{:.0f} MB; time "
                          "limit with 1.5x margin + 10 min: {}\n", clock_text(wall_s), worst_memory,
                          clock_text(1.5 * wall_s + 600));
  e.report += "  tasks:\n";
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const auto& p = entries[i];
    const auto& a = spec.samples_m[i];
    e.report += p.failure.empty()
                    ? fmt::format("    {}  ({:.4f}, {:.4f}, {:.4f})  f_1 {:8.1f} Hz  k {:5.2f}  h {:.4f} m  {:7} dofs  ~{:5} modes  "
                                  "~{}  (coarse {} dofs, transfer work {:.3g} per mode)\n", tasks[i].name, a[0], a[1], a[2],
                                  p.f1_hz, p.k, p.h_m, p.dofs, p.modes, clock_text(p.task_s), p.coarse_dofs, p.transfer_work)
                    : fmt::format("    {}  ({:.4f}, {:.4f}, {:.4f})  will fail: {}\n", tasks[i].name, a[0], a[1], a[2],
                                  p.failure);
  }
  return e;
}

}  // namespace clatter::jobs
