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

// The cost model, fitted to the 77 entries of the default bank built on one rank per task and on
// two (docs/benchmarks.md "The plan's cost model, refitted" and "The transfer's queue of modes,
// one rank per task or two"), each stage scaled by what the calibration entries, solved here on
// one rank, measure:
// - the eigen-solve on one rank ~ dofs^1.20 (1 + modes / 16): a fixed share (the slice's end
//   factorizations and the count check) and one per mode (shifts and solves with the factors);
// - the pre-solve (one factorization and a few Krylov restarts on the coarse mesh) like its dofs,
//   mesh and assembly like the entry's;
// - the FEM on a group of r ranks faster by r^(0.147 ln(dofs / 3800)), the exponent within [0, 1]:
//   2 ranks gain nothing below ~4000 dofs (median 1.00 over 7 entries), 1.20x at 10-30k, 1.37x at
//   70-120k (fitted on the 77 entries' FEM time at 1 and 2 ranks per task; 4 and more ranks are
//   extrapolated);
// - the transfer per mode a fixed part (the surface data, the multipole expansion) and one that
//   grows with the work of its layouts' fits (kernels/transfer layout_size: the QR's fit points x
//   unknowns^2 per parity class fitted, and the Green's functions of the fill and the check) to the
//   power 1.30, the fixed part worth work^1.30 = 3.4e10; a group's ranks take the modes from a
//   queue (modal_transfer.cpp), so r ranks take 1/r of the time (its core-seconds at 1 and 2 ranks
//   per task agree within 3 % per size class).
constexpr double kDofsExponent = 1.20;
constexpr double kModesPerFixedShare = 16;
constexpr double kEstimateExponent = 1.0;
// Factor memory of 3-D nested dissection grows like n^(4/3).
constexpr double kMemoryExponent = 4.0 / 3.0;
constexpr double kGroupSpeedupPerLogDofs = 0.147;
constexpr double kGroupSpeedupFromDofs = 3800;
double fem_group_speedup(long long dofs, int ranks_per_task) {
  const double exponent = std::clamp(kGroupSpeedupPerLogDofs * std::log(static_cast<double>(dofs) / kGroupSpeedupFromDofs), 0.0, 1.0);
  return std::pow(ranks_per_task, exponent);
}
constexpr double kTransferWorkExponent = 1.30;
constexpr double kTransferFixedWork = 3.4e10;
// The parity classes a mode fits (mode_transfer.cpp): one on a body of three distinct axes (the
// others are the mesh's noise, within TransferSettings::class_budget), two for most modes of a
// spheroid (a doublet's two modes mix their classes), most of the eight for a sphere's
// multiplets. As factors on the work, fitted with the constants above (the sphere's on the one
// sphere of the default bank).
constexpr double kSpheroidClassWork = 1.64;
constexpr double kSphereClassWork = 5.3;
double class_work_factor(const std::array<double, 3>& axes) {
  const auto same = [](double x, double y) { return std::abs(x - y) <= 1e-6 * std::max(x, y); };
  const int pairs = same(axes[0], axes[1]) + same(axes[1], axes[2]) + same(axes[0], axes[2]);
  return pairs == 3 ? kSphereClassWork : pairs == 1 ? kSpheroidClassWork : 1.0;
}
// The calibration: the few smallest entries, solved in full as the sweep will, each stage's scale
// their geometric mean, which tames one small entry's timing noise (docs/benchmarks.md "The plan's
// cost model, refitted").
constexpr std::size_t kCalibrationEntries = 3;

// The transfer's work per mode, averaged over the entry's band with the modes' density, which
// grows like f^2 on a bulky entry (Weyl) and like f on a flat one (a plate's).
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
  return class_work_factor(axes) * work / weight;
}

struct EntryPlan {
  double f1_hz = 0, k = 0, h_m = 0;
  double transfer_work = 0;  // per mode (transfer_work above)
  long long dofs = 0, coarse_dofs = 0, modes = 0;
  double fem_s = 0, transfer_s = 0, memory_mb = 0;  // on the task's group
  double task_s() const { return fem_s + transfer_s; }
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
  std::vector<std::size_t> cal;  // the calibration entries: the smallest that mesh
  for (std::size_t i = 0; i < entries.size(); ++i)
    if (entries[i].failure.empty()) cal.push_back(i);
  if (cal.empty()) throw InputError("plan: no entry of the sweep meshes; see mesh.* and patch.samples");
  std::sort(cal.begin(), cal.end(), [&](std::size_t x, std::size_t y) { return entries[x].dofs < entries[y].dofs; });
  cal.resize(std::min(cal.size(), kCalibrationEntries));
  // Each stage's model, per entry; `modes` the count the entry has (measured or predicted).
  const auto estimate_model = [](const EntryPlan& p) { return std::pow(static_cast<double>(p.coarse_dofs), kEstimateExponent); };
  const auto setup_model = [](const EntryPlan& p) { return static_cast<double>(p.dofs); };
  const auto solve_model = [](const EntryPlan& p, double modes) {
    return std::pow(static_cast<double>(p.dofs), kDofsExponent) * (1 + modes / kModesPerFixedShare);
  };
  const auto transfer_model = [](const EntryPlan& p, double modes) {
    return modes * (kTransferFixedWork + std::pow(p.transfer_work, kTransferWorkExponent));
  };
  // Each stage's scale: the geometric mean over the calibration entries of measured / model.
  // A floor of 1 ms keeps a stage too quick to time from taking the logarithm of zero.
  const auto at_least = [](double t_s) { return std::max(t_s, 1e-3); };
  double log_estimate = 0, log_setup = 0, log_solve = 0, log_transfer = 0, log_memory = 0;
  double found_modes = 0, coarse_modes = 0, cal_s = 0;
  std::string cal_text;
  for (const std::size_t i : cal) {
    const auto entry = build_modal_entry(MPI_COMM_SELF, spec, i);
    const auto& c = entry.cost;
    const double modes = static_cast<double>(std::max<std::size_t>(entry.modes(), 1));
    const double setup_s = c.mesh_s + c.assembly_s, solve_s = c.total_s - c.transfer_s - c.estimate_s - setup_s;
    log_estimate += std::log(at_least(c.estimate_s) / estimate_model(entries[i]));
    log_setup += std::log(at_least(setup_s) / setup_model(entries[i]));
    log_solve += std::log(at_least(solve_s) / solve_model(entries[i], modes));
    log_transfer += std::log(at_least(c.transfer_s) / transfer_model(entries[i], modes));
    // MUMPS' own figure: the process's resident size here also holds every pre-solve before it.
    log_memory += std::log(std::max(c.factor_memory_mb, 1.0) / std::pow(static_cast<double>(entry.mesh.dofs), kMemoryExponent));
    found_modes += modes;
    coarse_modes += static_cast<double>(std::max<long long>(entries[i].modes, 1));
    cal_s += c.total_s;
    cal_text += fmt::format("{}{} ({} dofs, {} modes: {:.1f} s + {:.1f} s transfer)", cal_text.empty() ? "" : ", ",
                            tasks[i].name, entry.mesh.dofs, entry.modes(), c.total_s - c.transfer_s, c.transfer_s);
  }
  const double n_cal = static_cast<double>(cal.size());
  const double estimate_scale = std::exp(log_estimate / n_cal), setup_scale = std::exp(log_setup / n_cal),
               solve_scale = std::exp(log_solve / n_cal), transfer_scale = std::exp(log_transfer / n_cal),
               memory_scale = std::exp(log_memory / n_cal);
  // The coarse mesh undercounts the top of the range (its frequencies are high): scaled by what
  // the calibration entries' fine solves found against their coarse counts.
  const double count_scale = found_modes / coarse_modes;
  PlanEstimate e;
  double core_s = 0, worst_memory = 0;
  for (auto& p : entries) {
    if (!p.failure.empty()) {
      e.task_s.push_back(0);
      continue;
    }
    p.modes = std::llround(static_cast<double>(p.modes) * count_scale);
    const double modes = static_cast<double>(p.modes);
    const double fem_s = estimate_scale * estimate_model(p) + setup_scale * setup_model(p) + solve_scale * solve_model(p, modes);
    p.fem_s = fem_s / fem_group_speedup(p.dofs, o.ranks_per_task);
    p.transfer_s = transfer_scale * transfer_model(p, modes) / o.ranks_per_task;
    p.memory_mb = memory_scale * std::pow(static_cast<double>(p.dofs), kMemoryExponent) / o.ranks_per_task;
    e.task_s.push_back(p.task_s());
    core_s += p.task_s() * o.ranks_per_task;
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
  e.report += fmt::format("  calibration: {} solved here in {:.1f} s: {}; time ~ (coarse dofs^{} + dofs + dofs^{} (1 + modes/{})) "
                          "/ ranks_per_task^({} ln(dofs/{}), within [0, 1]) + modes x ({:.2g} + (its layouts' work: QR per parity class "
                          "and Green's functions)^{}) / ranks_per_task, each part scaled by these entries\n",
                          cal.size() == 1 ? "the smallest entry" : fmt::format("the {} smallest entries", cal.size()), cal_s,
                          cal_text, kEstimateExponent, kDofsExponent, kModesPerFixedShare, kGroupSpeedupPerLogDofs, kGroupSpeedupFromDofs,
                          kTransferFixedWork, kTransferWorkExponent);
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
                                  "~{:7.1f} s = {:.1f} FEM + {:.1f} transfer  (coarse {} dofs, transfer work {:.3g} per mode)\n",
                                  tasks[i].name, a[0], a[1], a[2], p.f1_hz, p.k, p.h_m, p.dofs, p.modes, p.task_s(), p.fem_s,
                                  p.transfer_s, p.coarse_dofs, p.transfer_work)
                    : fmt::format("    {}  ({:.4f}, {:.4f}, {:.4f})  will fail: {}\n", tasks[i].name, a[0], a[1], a[2],
                                  p.failure);
  }
  return e;
}

}  // namespace clatter::jobs
