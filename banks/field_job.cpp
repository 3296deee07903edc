#include "banks/field_job.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "core/stage_log.hpp"
#include "io/h5_parallel.hpp"
#include "io/provenance.hpp"
#include "banks/commands.hpp"
#include "banks/medium_keys.hpp"
#include "cli/run_options.hpp"
#include "kernels/pulse.hpp"
#include "mpi/cart.hpp"
#include "mpi/collectives.hpp"
#include "mpi/comm.hpp"

namespace clatter::jobs {

const io::Schema& field_schema() {
  static const io::Schema schema = [] {
    io::Schema s{"clatter-bank field: free-field pressure of a psi-driven point monopole on a distributed grid",
                 medium_and_pulse_keys()};
    s.keys.insert(s.keys.end(), {
        {"grid.n_cells", std::int64_t{64}, "cells along each axis of the cubic grid", {2, 4096}},
        {"grid.dx_m", 0.01, "cell size [m]; the monopole sits at the grid's centre", {0.0, 10.0, true}},
        {"field.t_s", 6e-4, "time of the snapshot [s]; psi is centred on t = 0", {-1.0, 10.0}},
    });
    return s;
  }();
  return schema;
}

void run_field(MPI_Comm comm, const io::Config& config, const std::string& out_path, const std::string& command) {
  const int n = static_cast<int>(config.integer("grid.n_cells"));
  const double dx_m = config.real("grid.dx_m");
  const double c_m_s = config.real("medium.c_m_s");
  const double rho_kg_m3 = config.real("medium.rho_kg_m3");
  const double h_s = config.real("pulse.h_s");
  const double t_s = config.real("field.t_s");
  const int n_ranks = mpi::size(comm);

  std::optional<mpi::CartTopology> topo;
  {
    Stage stage("decompose");
    mpi::agree(comm, [&] { topo.emplace(comm, std::array<int, 3>{n, n, n}); });
  }
  const auto start = topo->local_start();
  const auto count = topo->local_count();
  const auto& dims = topo->dims();
  spdlog::info("field: {}^3 cells of {:.4g} mm on {} rank(s) as {}x{}x{} blocks", n, 1e3 * dx_m, n_ranks, dims[0],
               dims[1], dims[2]);
  spdlog::debug("field: this rank owns [{}, {}) x [{}, {}) x [{}, {})", start[0], start[0] + count[0], start[1],
                start[1] + count[1], start[2], start[2] + count[2]);

  // Cell centres, symmetric about the origin, so the source never sits on a sample (r > 0).
  auto centre_m = [&](int i) { return (i + 0.5 - 0.5 * n) * dx_m; };
  std::vector<float> p_pa(static_cast<std::size_t>(count[0]) * count[1] * count[2]);
  double local_peak_pa = 0;
  {
    Stage stage("sample");
    std::size_t idx = 0;
    for (int i = start[0]; i < start[0] + count[0]; ++i)
      for (int j = start[1]; j < start[1] + count[1]; ++j)
        for (int k = start[2]; k < start[2] + count[2]; ++k) {
          const double r = std::hypot(centre_m(i), centre_m(j), centre_m(k));
          const double p = kernels::monopole_pressure(r, t_s, h_s, c_m_s, rho_kg_m3);
          p_pa[idx++] = static_cast<float>(p);
          local_peak_pa = std::max(local_peak_pa, std::abs(p));
        }
  }
  const double peak_pa = mpi::all_reduce_max(comm, local_peak_pa);
  // The shell's crest travels at r = c t, where psi(0) = 7/9: the peak the grid should come close to.
  const double crest_r_m = c_m_s * t_s;
  if (crest_r_m > 0)
    spdlog::info("field: peak |p| = {:.4g} Pa on the grid; exact crest rho psi(0) / (4 pi c t) = {:.4g} Pa at r = {:.4g} m",
                 peak_pa, rho_kg_m3 * (7.0 / 9.0) / (4.0 * std::numbers::pi * crest_r_m), crest_r_m);

  {
    Stage stage("write");
    auto file = io::create_parallel(out_path, comm);
    io::write_header(file, kFieldFormat, kFieldFormatVersion);
    const io::Dims global{hsize_t(n), hsize_t(n), hsize_t(n)};
    io::write_dataset_block<float>(file, "/field/p", global, {hsize_t(start[0]), hsize_t(start[1]), hsize_t(start[2])},
                                   {hsize_t(count[0]), hsize_t(count[1]), hsize_t(count[2])}, p_pa, "Pa");
    std::vector<double> x_m(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) x_m[static_cast<std::size_t>(i)] = centre_m(i);
    io::write_dataset<double>(file, "/grid/x_m", x_m, {hsize_t(n)}, "m");
    io::write_attribute<double>(file, "/field", "t_s", t_s);
    io::write_attribute<double>(file, "/field", "h_s", h_s);
    io::write_attribute<double>(file, "/field", "c_m_s", c_m_s);
    io::write_attribute<double>(file, "/field", "rho_kg_m3", rho_kg_m3);
    io::write_attribute<double>(file, "/grid", "dx_m", dx_m);
    io::write_provenance(file, command, config.to_toml(), n_ranks);
    file.commit();
  }
  spdlog::info("field: wrote {} ({}^3 float32, {:.2f} MiB)", out_path, n,
               double(n) * n * n * sizeof(float) / (1024.0 * 1024.0));
}

Command add_field_command(CLI::App& parent) {
  return add_config_command(parent, "field",
                            "sample the exact pressure of a psi-driven monopole on a distributed grid and write it "
                            "with collective HDF5 (the foundation demo)",
                            field_schema(), "field.h5", "output HDF5 file",
                            [](const RunContext& context, const io::Config& config, const std::string& out) {
                              Stage stage("field");
                              run_field(context.world, config, out, context.command_line);
                            });
}

}  // namespace clatter::jobs
