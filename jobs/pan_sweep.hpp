#pragma once
// `clatter-bank pan` and `clatter-bank merge`: the PAN bank as a sweep (jobs/sweep.hpp) of
// proxy x field tasks, merged into one bank file.
#include <mpi.h>

#include <string>

#include "io/config.hpp"

namespace clatter::jobs {

struct PanSweepOptions {
  std::string out = "bank.h5";
  std::string results;            // empty: OUT.tasks
  int ranks_per_task = 1;
  bool resume = false;
  std::string slice;              // "K/N": job array element K of N (no merge); empty: everything
  bool keep_results = false;      // keep the task files after a complete merge
  bool force = false;             // the merge may replace any bank at OUT (jobs/output_guard.hpp)
  double progress_interval_s = 10;
  std::string command;            // for provenance and the resume hint
};

// Returns the exit code: kExitOk, kExitInterrupted or kExitTasksFailed (same on every rank).
int run_pan_sweep(MPI_Comm world, const io::Config& config, const PanSweepOptions& options);

// Merges a results folder into a bank (rank 0 works; collective for the error agreement).
// kExitOk, or kExitTasksFailed when tasks failed or are missing (the bank lists them).
int run_pan_merge(MPI_Comm world, const std::string& results_dir, const std::string& out, const std::string& command,
                  bool force);

}  // namespace clatter::jobs
