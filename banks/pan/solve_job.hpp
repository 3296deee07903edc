#pragma once
// `clatter-bank solve`: FDTD solves of the acoustic field around one rigid ellipsoid driven by the
// acceleration pulse psi(t; h) in each chosen rigid-body field (Chadwick et al. 2012 eq. 9), on a
// Cartesian decomposition over the ranks, recorded at listener points. Format: docs/formats.md.
#include <mpi.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "io/config.hpp"
#include "banks/pan/solve_spec.hpp"
#include "kernels/fdtd/kirchhoff.hpp"

namespace clatter::jobs {

struct SolveResult {
  std::vector<std::vector<float>> series;  // per field: [listener][sample], rank 0 only
  // Through the Kirchhoff surface, rank 0 only: per field, one series per far direction (R p
  // against the retarded time) and per surface listener.
  std::vector<std::vector<kernels::fdtd::KirchhoffSeries>> far, surface_series;
  double cell_updates_per_s = 0;
  long long cells = 0;  // per step, all ranks
  double bytes = 0;     // solver storage, all ranks
};

// Called on rank 0 with each field's assembled Kirchhoff surface (index into spec.fields) before
// it is freed: what a caller hears through the surface beyond the spec's own lists (a PAN task's
// directions, each aligned by its own fraction of a step).
using SurfaceHook = std::function<void(std::size_t field_index, const kernels::fdtd::SurfaceField& surface)>;

SolveResult run_solve(MPI_Comm comm, const SolveSpec& spec, double progress_interval_s, const SurfaceHook& hook = {});

// `clatter-bank solve`: one solve of the config, written as clatter-fdtd-raw.
Command add_solve_command(CLI::App& parent);

void write_raw(const std::string& path, const SolveSpec& spec, const SolveResult& result, const io::Config& config,
               const std::string& command, int n_ranks);

}  // namespace clatter::jobs
