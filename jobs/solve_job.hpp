#pragma once
// `clatter-bank solve`: FDTD solves of the acoustic field around one rigid ellipsoid driven by the
// acceleration pulse psi(t; h) in each chosen rigid-body field (Chadwick et al. 2012 eq. 9), on a
// Cartesian decomposition over the ranks, recorded at listener points. Format: docs/formats.md.
#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "io/config.hpp"
#include "kernels/fdtd/problem.hpp"

namespace clatter::jobs {

const io::Schema& solve_schema();

inline constexpr const char* kRawFormat = "clatter-fdtd-raw";
inline constexpr int kRawFormatVersion = 2;

// A validated solve: everything is checked here, before any stepping.
struct SolveSpec {
  kernels::fdtd::Problem problem;  // field set per solve
  std::vector<int> fields;         // 1..6, or {0} for the monopole
  std::vector<std::array<double, 3>> listeners_m;
  int i_time_zero = 0;             // sample index of t = 0 (the centre of psi)
  int n_samples = 0;               // samples per series, t_k = (k - i_time_zero) dt
};

// Throws InputError naming the key and value for any invalid combination.
SolveSpec make_solve_spec(const io::Config& config);

struct SolveResult {
  std::vector<std::vector<float>> series;  // per field: [listener][sample], rank 0 only
  double cell_updates_per_s = 0;
  long long cells = 0;  // per step, all ranks
  double bytes = 0;     // solver storage, all ranks
};

SolveResult run_solve(MPI_Comm comm, const SolveSpec& spec, double progress_interval_s);

void write_raw(const std::string& path, const SolveSpec& spec, const SolveResult& result, const io::Config& config,
               const std::string& command, int n_ranks);

}  // namespace clatter::jobs
