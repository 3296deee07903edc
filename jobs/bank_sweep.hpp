#pragma once
// What every bank kind's sweep shares (`clatter-bank pan`, `clatter-bank modal`, `merge`): the
// locks, the no-downgrade check, the sweep engine (jobs/sweep.hpp), the interrupt and slice
// messages, the merge into one bank file and the clean-up of the results folder. A bank kind
// gives its config text, task names, task runner and merge (BankSweep); this file does the rest.
#include <CLI/CLI.hpp>
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "jobs/sweep.hpp"
#include "model/sweep_status.hpp"

namespace clatter::jobs {

struct BankSweepOptions {
  std::string out;
  std::string results;            // empty: OUT.tasks
  int ranks_per_task = 1;
  bool resume = false;
  std::string slice;              // "K/N": job array element K of N (no merge); empty: everything
  bool keep_results = false;      // keep the task files after a complete merge
  bool force = false;             // the merge may replace any bank at OUT (jobs/output_guard.hpp)
  double progress_interval_s = 10;
  std::string command;            // for provenance and the resume hint
};

// A bank merged from a results folder (rank 0), before it is written.
struct MergedBank {
  model::SweepStatus sweep;
  std::function<void(const std::string& out, const std::string& command, int n_ranks)> write;
};

struct BankSweep {
  std::string kind;                 // "pan", "modal": prefixes log lines
  std::string summary;              // one line on what the sweep computes, logged when it starts
  std::string config_toml;          // the sweep's manifest; its hash is the sweep id
  std::vector<std::string> task_names;
  TaskRunner run_task;              // unused by a merge alone
  std::function<MergedBank(const std::string& results_dir)> merge;
};

// The --results, --ranks-per-task, --resume, --slice, --keep-results and --force options.
void add_sweep_options(CLI::App& app, BankSweepOptions& options);

// Collective. Returns kExitOk, kExitInterrupted or kExitTasksFailed (the same on every rank).
int run_bank_sweep(MPI_Comm world, const BankSweep& sweep, const BankSweepOptions& options);
// Merges a results folder into a bank (rank 0 works; collective for the error agreement).
int run_bank_merge(MPI_Comm world, const BankSweep& sweep, const std::string& results_dir, const std::string& out,
                   const std::string& command, bool force);

}  // namespace clatter::jobs
