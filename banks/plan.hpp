#pragma once
// `clatter-bank plan`: what a sweep will cost before it is submitted, and ready Slurm batch scripts
// (docs/cluster.md). Each bank kind estimates its own tasks (BankKind::plan; PAN: cells x steps
// per task from a calibration solve measured here, banks/pan/pan_plan.cpp; modal: each entry's
// mesh and mode count, from one entry solved here, banks/modal/modal_plan.cpp); this file's
// command turns the estimate into a schedule and the batch scripts.
#include <mpi.h>

#include <string>
#include <vector>

#include "io/config.hpp"

namespace clatter::jobs {

struct PlanOptions {
  std::string kind = "pan";    // the bank kind's name
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

// What a plan predicts: the report's lines and each task's wall time on its group.
struct PlanEstimate {
  std::string report;
  std::vector<double> task_s;
  int nodes = 1;
  // Slurm's SIGTERM this long before the limit: a task polls it only between its stages, so the
  // lead must let the longest one finish and be written.
  int signal_lead_s = 120;
};

// The predicted wall time of these tasks handed out in order to `groups` groups, each taking the
// next task when it is free (sweep/sweep.hpp's dynamic hand-out).
double list_schedule_s(const std::vector<double>& task_s, int groups);

}  // namespace clatter::jobs
