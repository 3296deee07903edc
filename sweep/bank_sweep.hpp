#pragma once
// What every bank kind's sweep shares (`clatter-bank pan|modal|ground`, `merge`): the locks, the
// no-downgrade check, the sweep engine (sweep/sweep.hpp), the interrupt and slice messages, the
// merge into one bank file and the clean-up of the results folder. A bank kind gives its manifest
// (kind and config text), task names, task runner and merge (BankSweep); this file does the rest.
#include <CLI/CLI.hpp>
#include <mpi.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/sweep_status.hpp"
#include "sweep/sweep.hpp"

namespace clatter::jobs {

// A bank merged from a results folder (rank 0), before it is written.
struct MergedBank {
  model::SweepStatus sweep;
  std::function<void(const std::string& out, const std::string& command, int n_ranks)> write;
};

struct BankSweep {
  SweepManifest manifest;           // the kind (prefixes log lines) and the config; its hash is the sweep id
  std::string summary;              // one line on what the sweep computes, logged when it starts
  std::vector<std::string> task_names;
  TaskRunner run_task;              // unused by a merge alone
  std::function<MergedBank(const std::string& results_dir)> merge;
};

// The merge of a kind whose bank model `Bank` carries its SweepStatus as `bank.sweep`: `build`
// assembles the model from a results folder, `write` writes it to OUT.
template <class Bank>
std::function<MergedBank(const std::string&)> bank_merge(
    std::function<Bank(const std::string& results_dir)> build,
    std::function<void(const std::string& out, const Bank& bank, const std::string& command, int n_ranks)> write) {
  return [build = std::move(build), write = std::move(write)](const std::string& results_dir) {
    auto bank = std::make_shared<const Bank>(build(results_dir));
    return MergedBank{bank->sweep, [bank, write](const std::string& out, const std::string& command, int n_ranks) {
                        write(out, *bank, command, n_ranks);
                      }};
  };
}

// The --results, --ranks-per-task, --resume, --slice, --keep-results and --force options.
void add_sweep_options(CLI::App& app, SweepOptions& options);

// Collective. Returns kExitOk, kExitInterrupted or kExitTasksFailed (the same on every rank).
int run_bank_sweep(MPI_Comm world, const BankSweep& sweep, const SweepOptions& options, const std::string& command);
// Merges a results folder into a bank (rank 0 works; collective for the error agreement).
int run_bank_merge(MPI_Comm world, const BankSweep& sweep, const std::string& results_dir, const std::string& out,
                   const std::string& command, bool force);

}  // namespace clatter::jobs
