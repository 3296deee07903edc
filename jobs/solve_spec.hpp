#pragma once
// The input contract of `clatter-bank solve`: its config schema and the validated SolveSpec that
// every FDTD solve (a solve job, or one proxy of a PAN sweep) runs from.
#include <array>
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

}  // namespace clatter::jobs
