#pragma once
// One task of the ground bank (docs/ground.md): for one ground material and listener elevation,
// the Rayleigh integral of Lamb's step response (the volume series phi(s), the expensive part,
// once), then Pi(t_hat) for every eta of the grid from it; the task file; the merge into the bank.
#include <mpi.h>

#include <string>
#include <vector>

#include "banks/ground/ground_spec.hpp"
#include "sweep/sweep.hpp"
#include "model/ground_bank.hpp"

namespace clatter::jobs {

// The series of one (material, elevation) for every eta, in eta order. Serial and deterministic:
// every rank of a group computes the same row (a group larger than one rank only repeats it), so
// a failure (TaskFailure: the kernel refused or returned a non-finite value) or an interruption
// (Interrupted, polled over `group` between the stages) is raised alike on every rank.
std::vector<model::GroundSeries> build_ground_row(MPI_Comm group, const GroundSpec& spec, const GroundTask& task);

// The sweep's task: build_ground_row and, on the group leader, the writer of its task file.
TaskWriter run_ground_task(MPI_Comm group, const GroundSpec& spec, const GroundTask& task);

// The bank from a results folder: every task found done; a failed or missing (material,
// elevation) leaves that elevation out of the material's grid (a material with none is left
// out) and is listed in the bank's /sweep.
model::GroundBank merge_ground_results(const GroundSpec& spec, const std::string& results_dir,
                                       const std::string& config_toml);

}  // namespace clatter::jobs
