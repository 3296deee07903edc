#include "banks/ground/ground_job.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "banks/ground/ground_series.hpp"
#include "io/ground_bank.hpp"
#include "io/sweep_files.hpp"
#include "kernels/ground/lamb.hpp"
#include "mpi/comm.hpp"
#include "mpi/interrupt.hpp"

namespace clatter::jobs {
namespace {

double degrees(double rad) { return rad * 180 / std::numbers::pi; }

// The kernel's refusals and numerical failures are the task's, recorded by the sweep; the row is
// the same on every rank, so they are too.
template <class F>
auto or_fail(const std::string& what, F&& f) {
  try {
    return f();
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    throw TaskFailure(what + ": " + e.what());
  }
}

void check_finite(const model::GroundSeries& s, double eta) {
  for (std::size_t k = 0; k < s.pi.size(); ++k)
    if (!std::isfinite(s.pi[k]))
      throw TaskFailure(fmt::format("eta = {}: Pi[{}] (t_hat = {}) is {}", eta, k,
                                    s.t_hat_start + static_cast<double>(k) * s.dt_hat, s.pi[k]));
}

}  // namespace

std::vector<model::GroundSeries> build_ground_row(MPI_Comm group, const GroundSpec& spec, const GroundTask& task) {
  kernels::ground::VolumeSeries volume;
  {
    Stage stage("volume");
    volume = or_fail("the volume series", [&] { return ground_volume(spec, task.material, task.elevation); });
  }
  for (std::size_t k = 0; k < volume.phi.size(); ++k)
    if (!std::isfinite(volume.phi[k])) throw TaskFailure(fmt::format("the volume series: phi[{}] is {}", k, volume.phi[k]));
  for (std::size_t k = 0; k < volume.tail.g.size(); ++k)
    if (!std::isfinite(volume.tail.g[k])) throw TaskFailure(fmt::format("the volume series' tail: g[{}] is {}", k, volume.tail.g[k]));
  const GroundWindow w = ground_window(spec, task.material, task.elevation);
  std::vector<model::GroundSeries> row;
  Stage stage("pressure");
  for (double eta : spec.eta) {
    mpi::poll_interrupt(group, fmt::format("the pressure at eta = {}", eta));
    model::GroundSeries s = or_fail(fmt::format("the pressure at eta = {}", eta), [&] { return ground_series(spec, w, volume, eta); });
    check_finite(s, eta);
    if (s.pi.size() < 2) throw TaskFailure(fmt::format("eta = {}: {} samples of Pi; the window holds none", eta, s.pi.size()));
    row.push_back(std::move(s));
  }
  return row;
}

TaskWriter run_ground_task(MPI_Comm group, const GroundSpec& spec, const GroundTask& task) {
  const auto t0 = std::chrono::steady_clock::now();
  mpi::poll_interrupt(group, "the volume series");
  auto row = build_ground_row(group, spec, task);
  if (mpi::rank(group) != 0) return {};
  std::size_t samples = 0;
  for (const auto& s : row) samples += s.pi.size();
  const auto& m = spec.materials[task.material];
  spdlog::info("ground: {} ({}, elevation {:.4g} deg): {} series, {} samples of Pi; {:.1f} s", task.name, m.name,
               degrees(spec.elevation_rad[task.elevation]), row.size(), samples,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return [row = std::move(row)](io::File& file, const std::string& group_name) {
    io::write_ground_task(file, group_name, row);
  };
}

model::GroundBank merge_ground_results(const GroundSpec& spec, const std::string& results_dir,
                                       const std::string& config_toml) {
  model::GroundBank bank;
  bank.c0_m_s = spec.c0_m_s;
  bank.rho0_kg_m3 = spec.rho0_kg_m3;
  const auto tasks = ground_tasks(spec);
  bank.sweep.sweep_id = io::sweep_id(config_toml);
  bank.sweep.tasks_total = static_cast<std::uint32_t>(tasks.size());
  std::vector<model::GroundMaterial> materials = spec.materials;
  for (auto& m : materials) m.elevation_rad.clear();
  for (const auto& t : tasks) {
    auto& m = materials[t.material];
    const double theta = spec.elevation_rad[t.elevation];
    const std::string label = fmt::format("{} ({}, elevation {:.4g} deg)", t.name, m.name, degrees(theta));
    if (!task_done(results_dir, t.name, label, config_toml, bank.sweep)) continue;
    auto file = io::File::open(io::task_path(results_dir, t.name));
    auto row = io::read_ground_task(file, "/result", spec.eta.size());
    m.elevation_rad.push_back(theta);  // tasks come in elevation order within a material
    for (auto& s : row) m.series.push_back(std::move(s));
  }
  for (auto& m : materials)
    if (!m.elevation_rad.empty()) bank.materials.push_back(std::move(m));
  return bank;
}

}  // namespace clatter::jobs
