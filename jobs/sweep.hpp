#pragma once
// The sweep engine: a bank is a list of independent tasks (PAN: proxy x field), farmed out to
// groups of --ranks-per-task ranks. Every finished task lands atomically as one HDF5 file in a
// results folder (docs/cluster.md, "Sweeps"):
//   RESULTS/sweep.toml     the config of the sweep; tasks of another config are refused
//   RESULTS/TASK.h5        format clatter-sweep-task v1: status done (payload in /result) or
//                          failed (reason), and a content hash over everything else
// Hand-out is dynamic: group leaders take the next pending task from a counter on world rank 0
// with MPI_Fetch_and_op (passive-target one-sided MPI; no rank is kept back as a master). A task's
// content does not depend on who ran it or when, so any grouping, order, interruption and resume
// give byte-identical results.
#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/sweep_files.hpp"
#include "jobs/output_guard.hpp"

namespace clatter::jobs {

struct SweepOptions {
  std::string results_dir;
  int ranks_per_task = 1;
  bool resume = false;
  int slice_index = 0, slice_count = 1;  // a job array element runs tasks t with t % count == index
  double progress_interval_s = 10;
};

// Writes a finished task's payload into its file under the given group (called on the group leader).
using TaskWriter = io::TaskPayloadWriter;
// Runs task `task` on every rank of `group` (collectively) and returns, on the group's rank 0, the
// writer of its result. Throws TaskFailure (the sweep records it and goes on) or Interrupted;
// both must be raised on every rank of the group alike.
using TaskRunner = std::function<TaskWriter(MPI_Comm group, std::size_t task)>;

struct SweepReport {
  std::size_t total = 0;         // tasks of the sweep (all slices)
  std::size_t in_slice = 0;      // tasks this run was responsible for
  std::size_t done_before = 0;   // found finished and verified (--resume)
  std::size_t done_now = 0;
  std::size_t failed = 0;        // failed in this run (recorded with their reasons)
  bool interrupted = false;
};

// Collective over `world`. `names[t]` names task t (file-name safe, unique). `locks` (taken on
// options.results_dir and the slice) make this run the folder's one writer.
SweepReport run_sweep(MPI_Comm world, const SweepLocks& locks, const std::vector<std::string>& names,
                      const std::string& config_toml, const SweepOptions& options, const TaskRunner& runner);

// The refusal of a task file that names another sweep: its path and both sweep ids.
InputError foreign_task_error(const std::string& path, const io::TaskRecord& record, const std::string& config_toml);
// What a merge finds for task `name`: true when its file is done (the caller reads its payload);
// otherwise the task is added to `status` as failed (with its reason, labelled `label`) or
// missing. A task file of another sweep is refused (foreign_task_error).
bool task_done(const std::string& results_dir, const std::string& name, const std::string& label,
               const std::string& config_toml, model::SweepStatus& status);
// The config a results folder was made with (InputError if it has none).
std::string read_sweep_config(const std::string& results_dir);

}  // namespace clatter::jobs
