#pragma once
// The files of a sweep (sweep/sweep.hpp, docs/formats.md "Sweep task files"): one task file per
// finished task in the results folder, and the /sweep group of every bank a sweep builds.
//   TASK.h5  format clatter-sweep-task v1; root attributes sweep_id, task, status ("done", payload
//            in /result; or "failed", with its reason) and content_hash over everything else.
//   /sweep   of a bank: sweep_id, tasks_total, n_failed, n_missing, failed, missing.
// A sweep's id is the hash of its config as TOML: task files and banks of one sweep share it, so
// a merge can tell a task file or a bank of another sweep from its own.
#include <functional>
#include <string>

#include "io/h5.hpp"
#include "model/sweep_status.hpp"

namespace clatter::io {

inline constexpr const char* kTaskFormat = "clatter-sweep-task";
inline constexpr int kTaskFormatVersion = 1;

std::string sweep_id(const std::string& config_toml);
std::string task_path(const std::string& results_dir, const std::string& name);

// Writes the task's payload under `group` of its file.
using TaskPayloadWriter = std::function<void(File& file, const std::string& group)>;
// Atomic (File::commit). `payload` is null for a failed task.
void write_task_file(const std::string& path, const std::string& sweep_id, const std::string& name,
                     const std::string& status, const std::string& reason, const TaskPayloadWriter* payload);

enum class TaskState { missing, done, failed, invalid, foreign };
struct TaskRecord {
  TaskState state = TaskState::missing;
  // failed: why the task failed; invalid: what is wrong with the file; foreign: its sweep id.
  std::string reason;
};
// What the task file at `path` says about task `name` of sweep `sweep_id`: its format and content
// hash are checked before anything it says is believed.
TaskRecord inspect_task(const std::string& path, const std::string& name, const std::string& sweep_id);

void write_sweep_status(File& file, const model::SweepStatus& status);
// Banks written before sweep ids were stored read with an empty sweep_id (of no known sweep).
model::SweepStatus read_sweep_status(const File& file);

}  // namespace clatter::io
