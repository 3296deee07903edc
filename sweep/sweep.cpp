#include "sweep/sweep.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "core/stage_log.hpp"
#include "io/text_file.hpp"
#include "cli/run_options.hpp"
#include "mpi/collectives.hpp"
#include "mpi/comm.hpp"
#include "mpi/groups.hpp"
#include "mpi/interrupt.hpp"
#include "mpi/shared_counter.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

std::string manifest_path(const std::string& dir) { return (fs::path(dir) / "sweep.toml").string(); }

// The folder and its sweep.toml: created on a fresh start, compared on every later start (job
// array elements and resumed runs share it).
void prepare_results_dir(const std::string& dir, const SweepManifest& manifest) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(fmt::format("--results {}: cannot create the folder: {}", dir, ec.message()));
  const std::string path = manifest_path(dir);
  if (fs::exists(path)) {
    const SweepManifest found = read_sweep_manifest(dir);
    if (found.config_toml != manifest.config_toml || found.kind != manifest.kind)
      throw InputError(fmt::format("--results {}: holds a sweep of another config (see {}); use another folder or the "
                                   "same config",
                                   dir, path));
    return;
  }
  const std::string temp = fmt::format("{}/.sweep.toml.tmp-{}", dir, ::getpid());
  {
    std::ofstream out(temp, std::ios::binary);
    out << manifest.text();
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + temp);
  }
  fs::rename(temp, path);
}

// Temporaries of task files a killed run left behind (only this slice's: other array elements may
// be writing theirs right now).
int remove_stale_temporaries(const std::string& dir, const std::vector<std::string>& names,
                             const std::vector<std::size_t>& slice) {
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string file = entry.path().filename().string();
    for (std::size_t t : slice)
      if (file.rfind("." + names[t] + ".h5.tmp-", 0) == 0) removed += fs::remove(entry.path()) ? 1 : 0;
  }
  return removed;
}

// The slots of the sweep's mpi::SharedCounter, advanced by group leaders.
enum CounterSlot { kNext = 0, kDone = 1, kFailed = 2, kSlots = 3 };

// The tasks of this slice of the sweep: t with t % slice_count == slice_index.
std::vector<std::size_t> slice_tasks(std::size_t n_tasks, Slice s) {
  if (s.count < 1 || s.index < 0 || s.index >= s.count)
    throw InputError(fmt::format("--slice {}/{}: needs 0 <= index < count", s.index, s.count));
  std::vector<std::size_t> slice;
  for (std::size_t t = static_cast<std::size_t>(s.index); t < n_tasks; t += static_cast<std::size_t>(s.count))
    slice.push_back(t);
  return slice;
}

// On rank 0: prepares the folder, counts the slice's verified finished tasks into `done_before`
// and returns the others, the tasks still to run.
std::vector<std::uint64_t> scan_results(const std::vector<std::string>& names, const std::vector<std::size_t>& slice,
                                        const SweepManifest& manifest, const SweepOptions& o, std::size_t& done_before) {
  Stage stage("scan results");
  const std::string results_dir = o.results_dir();
  prepare_results_dir(results_dir, manifest);
  std::vector<std::uint64_t> pending;
  std::size_t present = 0;
  const std::string id = manifest.id();  // hashed once, not per task
  for (std::size_t t : slice) {
    const std::string path = io::task_path(results_dir, names[t]);
    const io::TaskRecord r = io::inspect_task(path, names[t], id);
    if (r.state == io::TaskState::foreign) throw foreign_task_error(path, r, manifest.config_toml);
    if (r.state != io::TaskState::missing) ++present;
    if (r.state == io::TaskState::done) {
      ++done_before;
      continue;
    }
    if (o.resume && r.state == io::TaskState::failed)
      spdlog::info("sweep: retrying {} (failed before: {})", names[t], r.reason);
    if (o.resume && r.state == io::TaskState::invalid) spdlog::warn("sweep: redoing {}: {}", names[t], r.reason);
    pending.push_back(t);
  }
  if (present > 0 && !o.resume)
    throw InputError(fmt::format("--results {}: already holds {} of this sweep's task files; add --resume to go on "
                                 "(finished tasks are kept) or use another folder",
                                 results_dir, present));
  if (const int n = remove_stale_temporaries(results_dir, names, slice); n > 0)
    spdlog::info("sweep: removed {} temporary file(s) of an earlier run that was killed", n);
  return pending;
}

// Rank 0 looks at the folder (its lock still held); everybody gets the list of pending tasks and `done_before`.
std::vector<std::size_t> find_pending(MPI_Comm world, const SweepLocks& locks, const std::vector<std::string>& names,
                                      const std::vector<std::size_t>& slice, const SweepManifest& manifest,
                                      const SweepOptions& o, std::size_t& done_before) {
  std::vector<std::uint64_t> pending;
  mpi::agree(world, [&] {
    if (mpi::rank(world) != 0) return;
    locks.check_held();
    pending = scan_results(names, slice, manifest, o, done_before);
  });
  pending = mpi::broadcast(world, std::move(pending));
  done_before = static_cast<std::size_t>(mpi::broadcast(world, static_cast<std::uint64_t>(done_before)));
  return {pending.begin(), pending.end()};
}

// What the per-task bookkeeping of one run needs to know.
struct SweepRun {
  const std::vector<std::string>& names;
  const std::string& results_dir;
  const std::string& id;  // the sweep id stamped into every task file
  std::size_t n_pending;  // tasks handed out in this run
  std::size_t n_slice;    // tasks of the slice, finished before included
  std::chrono::steady_clock::time_point start;  // of the hand-out, for the rate and the ETA
};

struct NextTask {
  bool stop = false;   // the group stops (interrupted)
  long long next = -1;  // index into the pending list; at or past its end when none is left
};

// The whole group agrees to stop, then the leader takes the next task for it.
NextTask take_next_task(const mpi::TaskGroups& groups, mpi::SharedCounter& counters) {
  MPI_Comm group = groups.group();
  const bool stop = mpi::interrupt_seen(group);
  long long next = -1;
  if (groups.is_leader() && !stop) next = counters.add(kNext, 1);
  next = mpi::broadcast(group, next);
  return {stop, next};
}

struct TaskOutcome {
  TaskWriter writer;        // done: writes the result (on the group leader)
  std::string failure;      // failed: why
  bool interrupted = false;
};

// Runs one task on every rank of the group; the failures a sweep records and an interrupt come
// back as the outcome, anything else propagates.
TaskOutcome run_task(const TaskRunner& runner, MPI_Comm group, std::size_t task) {
  TaskOutcome outcome;
  try {
    outcome.writer = runner(group, task);
  } catch (const Interrupted& e) {
    outcome.interrupted = true;  // collective: every rank of the group is here
  } catch (const TaskFailure& e) {
    outcome.failure = e.what();  // collective too
  } catch (const InputError& e) {
    outcome.failure = e.what();  // raised alike on every rank by contract (core/errors.hpp)
  }
  return outcome;
}

// On the group leader: writes the task's file, done or failed with its reason (also when the result
// cannot be written). Returns the failure, empty when done.
std::string record_task(const SweepRun& run, std::size_t task, const TaskOutcome& outcome) {
  const std::string& name = run.names[task];
  const std::string path = io::task_path(run.results_dir, name);
  std::string failure = outcome.failure;
  if (failure.empty()) {
    try {
      Stage stage("write task");
      io::write_task_file(path, run.id, name, "done", "", &outcome.writer);
    } catch (const std::exception& e) {
      failure = fmt::format("writing the result: {}", e.what());
    }
  }
  if (!failure.empty()) {
    spdlog::error("sweep: task {} failed: {}", name, failure);
    try {
      io::write_task_file(path, run.id, name, "failed", failure, nullptr);
    } catch (const std::exception& e) {
      spdlog::error("sweep: cannot record the failure of {} either: {}", name, e.what());
    }
  }
  return failure;
}

// On the group leader: records the task, counts it (here and on the shared counters) and logs the
// progress of the whole run.
void finish_task(mpi::SharedCounter& counters, const SweepRun& run, std::size_t task, const TaskOutcome& outcome,
                 std::chrono::steady_clock::time_point task_start, SweepReport& report) {
  const std::string failure = record_task(run, task, outcome);
  if (!failure.empty()) {
    ++report.failed;
    counters.add(kFailed, 1);
  } else {
    ++report.done_now;
  }
  const long long finished = counters.add(kDone, 1) + 1;
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - run.start).count();
  const double per_hour = 3600.0 * static_cast<double>(finished) / std::max(elapsed_s, 1e-9);
  const double left = static_cast<double>(static_cast<long long>(run.n_pending) - finished);
  spdlog::info("sweep: {} {} in {:.1f} s; {}/{} tasks finished ({} failed), {:.0f} tasks/h, ETA {}", run.names[task],
               failure.empty() ? "done" : "FAILED",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - task_start).count(),
               finished + static_cast<long long>(report.done_before), run.n_slice,
               counters.add(kFailed, 0), per_hour, clock_text(3600.0 * left / std::max(per_hour, 1e-9)));
}

// Every group takes pending tasks and runs them until none is left or it is interrupted.
void hand_out_tasks(const mpi::TaskGroups& groups, mpi::SharedCounter& counters, const TaskRunner& runner,
                    const std::vector<std::size_t>& pending, const SweepRun& run, SweepReport& report) {
  for (;;) {
    const NextTask next = take_next_task(groups, counters);
    if (next.stop) {
      report.interrupted = true;
      break;
    }
    if (next.next < 0 || next.next >= static_cast<long long>(pending.size())) break;
    const std::size_t task = pending[static_cast<std::size_t>(next.next)];
    const auto task_start = std::chrono::steady_clock::now();
    const TaskOutcome outcome = run_task(runner, groups.group(), task);
    if (outcome.interrupted) {
      report.interrupted = true;
      break;
    }
    if (groups.is_leader()) finish_task(counters, run, task, outcome, task_start, report);
  }
}

// Totals over the groups (counted on leaders only).
void reduce_over_groups(MPI_Comm world, bool leader, SweepReport& report) {
  const std::array<long long, 2> local = {leader ? static_cast<long long>(report.done_now) : 0,
                                         leader ? static_cast<long long>(report.failed) : 0};
  const std::array<long long, 2> sum = mpi::all_reduce_sum(world, local);
  report.done_now = static_cast<std::size_t>(sum[0]);
  report.failed = static_cast<std::size_t>(sum[1]);
  report.interrupted = mpi::any(world, report.interrupted);
}

}  // namespace

bool task_done(const std::string& results_dir, const std::string& name, const std::string& label,
               const std::string& config_toml, model::SweepStatus& status) {
  const std::string path = io::task_path(results_dir, name);
  const io::TaskRecord record = io::inspect_task(path, name, status.sweep_id);
  if (record.state == io::TaskState::foreign) throw foreign_task_error(path, record, config_toml);
  if (record.state == io::TaskState::failed) status.failed.push_back(label + ": " + record.reason);
  if (record.state == io::TaskState::invalid) status.failed.push_back(label + ": unreadable result: " + record.reason);
  if (record.state == io::TaskState::missing) status.missing.push_back(label);
  return record.state == io::TaskState::done;
}

std::string SweepManifest::text() const { return fmt::format("kind = \"{}\"\n{}", kind, config_toml); }

Slice parse_slice(const std::string& text) {
  Slice s;
  if (text.empty()) return s;
  char slash = 0;
  std::size_t used = 0;
  try {
    s.index = std::stoi(text, &used);
    slash = used < text.size() ? text[used] : 0;
    s.count = std::stoi(text.substr(used + 1));
  } catch (const std::exception&) {
    slash = 0;
  }
  if (slash != '/' || s.count < 1 || s.index < 0 || s.index >= s.count)
    throw InputError(fmt::format("--slice '{}': expected K/N with 0 <= K < N (e.g. $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)", text));
  return s;
}

SweepManifest read_sweep_manifest(const std::string& results_dir) {
  const std::string path = manifest_path(results_dir);
  if (!fs::exists(path)) throw InputError(fmt::format("{}: not a sweep results folder (no sweep.toml)", results_dir));
  const std::string text = io::read_text_file(path, "the sweep manifest");
  // The first line names the kind; the rest is the config exactly as the sweep hashed it.
  const std::size_t end = text.find('\n');
  const std::string first = text.substr(0, end);
  constexpr std::string_view prefix = "kind = \"";
  if (end == std::string::npos || first.rfind(prefix, 0) != 0 || first.size() < prefix.size() + 2 || first.back() != '"')
    throw InputError(fmt::format("{}: line 1 must name the bank kind, e.g. kind = \"modal\" (a results folder of a "
                                 "clatter-bank that did not record it: add that line for the kind it was run as)",
                                 path));
  return {first.substr(prefix.size(), first.size() - prefix.size() - 1), text.substr(end + 1)};
}

InputError foreign_task_error(const std::string& path, const io::TaskRecord& record, const std::string& config_toml) {
  return InputError(fmt::format("{}: a task file of another sweep (sweep id {}, this sweep's is {}); move it away",
                                path, record.reason, io::sweep_id(config_toml)));
}

SweepReport run_sweep(MPI_Comm world, const SweepLocks& locks, const SweepManifest& manifest,
                      const std::vector<std::string>& names, const SweepOptions& o, Slice s, const TaskRunner& runner) {
  install_interrupt_handlers();
  SweepReport report;
  report.total = names.size();
  const std::vector<std::size_t> slice = slice_tasks(names.size(), s);
  report.in_slice = slice.size();
  const std::string id = manifest.id();
  const std::string results_dir = o.results_dir();
  std::optional<mpi::TaskGroups> groups_storage;  // first: a bad --ranks-per-task creates nothing
  mpi::agree(world, [&] { groups_storage.emplace(world, o.ranks_per_task); });
  const mpi::TaskGroups& groups = *groups_storage;

  const std::vector<std::size_t> pending = find_pending(world, locks, names, slice, manifest, o, report.done_before);
  spdlog::info("sweep: {} tasks in this run ({} of {} in slice {}/{}, {} already done), {} group(s) of {} rank(s), "
               "results in {}",
               pending.size(), slice.size(), names.size(), s.index, s.count, report.done_before,
               groups.n_groups(), o.ranks_per_task, results_dir);
  // Lives until after the reduction: freeing its window is collective over the world.
  mpi::SharedCounter counters(world, kSlots);
  const SweepRun run{names, results_dir, id, pending.size(), slice.size(), std::chrono::steady_clock::now()};
  hand_out_tasks(groups, counters, runner, pending, run, report);
  reduce_over_groups(world, groups.is_leader(), report);
  return report;
}

}  // namespace clatter::jobs
