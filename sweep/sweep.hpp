#pragma once
// The sweep engine: a bank is a list of independent tasks (PAN: proxy x field), farmed out to
// groups of --ranks-per-task ranks. Every finished task lands atomically as one HDF5 file in a
// results folder (docs/cluster.md, "Sweeps"):
//   RESULTS/sweep.toml     the manifest: the bank kind, then the config of the sweep; tasks of
//                          another config are refused
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
#include "sweep/output_guard.hpp"

namespace clatter::jobs {

// What a sweep computes, as its results folder records it in sweep.toml: the bank kind (a line
// `kind = "NAME"` first) and the config text. The sweep id is the hash of the config text alone,
// so a bank's sweep id does not depend on how the manifest is laid out.
struct SweepManifest {
  std::string kind;         // the registry's name of the bank kind: "pan", "modal", "ground"
  std::string config_toml;  // the sweep's config as resolved (materials included)
  std::string text() const;
  std::string id() const { return io::sweep_id(config_toml); }
};
// The manifest of a results folder (InputError naming the file if it has none, or no kind line).
SweepManifest read_sweep_manifest(const std::string& results_dir);

// A job array element runs tasks t with t % count == index.
struct Slice {
  int index = 0, count = 1;
};
// "K/N" (empty: the whole sweep); InputError naming --slice otherwise.
Slice parse_slice(const std::string& text);

// The command-line options of a sweep (sweep/bank_sweep.hpp declares them).
struct SweepOptions {
  std::string out;
  std::string results;            // empty: OUT.tasks (results_dir())
  int ranks_per_task = 1;
  bool resume = false;
  std::string slice;              // "K/N": job array element K of N (no merge); empty: everything
  bool keep_results = false;      // keep the task files after a complete merge
  bool force = false;             // the merge may replace any bank at OUT (sweep/output_guard.hpp)
  std::string results_dir() const { return results.empty() ? out + ".tasks" : results; }
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
// the results folder and the slice) make this run the folder's one writer.
SweepReport run_sweep(MPI_Comm world, const SweepLocks& locks, const SweepManifest& manifest,
                      const std::vector<std::string>& names, const SweepOptions& options, Slice slice,
                      const TaskRunner& runner);

// The refusal of a task file that names another sweep: its path and both sweep ids.
InputError foreign_task_error(const std::string& path, const io::TaskRecord& record, const std::string& config_toml);
// What a merge finds for task `name`: true when its file is done (the caller reads its payload);
// otherwise the task is added to `status` as failed (with its reason, labelled `label`) or
// missing. A task file of another sweep is refused (foreign_task_error).
bool task_done(const std::string& results_dir, const std::string& name, const std::string& label,
               const std::string& config_toml, model::SweepStatus& status);

}  // namespace clatter::jobs
