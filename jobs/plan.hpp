#pragma once
// `clatter-bank plan`: what a PAN sweep will cost before it is submitted: the tasks, cells x steps
// per task, memory per rank and a predicted wall time from a calibration solve measured on this
// machine; and ready Slurm batch scripts (docs/cluster.md).
#include <mpi.h>

#include <string>

#include "io/config.hpp"

namespace clatter::jobs {

struct PlanOptions {
  int ranks = 1;               // MPI ranks of the job
  int ranks_per_task = 1;
  int cores_per_node = 0;      // 0: this machine's
  double rate = 0;             // cell-updates/s per rank; 0: measure now
  std::string config_path;     // the config the job will read (absolute path written into scripts)
  std::string out = "bank.h5";
  std::string results;         // empty: OUT.tasks
  std::string sbatch;          // write a batch script here
  int array = 0;               // > 0: a job array of this many elements plus a merge job
  std::string binary;          // clatter-bank to call in the scripts
};

// Runs on rank 0 (the calibration solve is serial); returns the text to print.
std::string run_plan(const io::Config& config, const PlanOptions& options);

}  // namespace clatter::jobs
