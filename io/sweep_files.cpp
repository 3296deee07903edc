#include "io/sweep_files.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "core/errors.hpp"
#include "io/content_hash.hpp"
#include "io/provenance.hpp"

namespace clatter::io {
namespace {

const HashExclusions kTaskHashExclusions{{}, {"content_hash"}};

std::string join_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  for (std::size_t p = 0, e; p < text.size(); p = e + 1) {
    e = text.find('\n', p);
    if (e == std::string::npos) e = text.size();
    if (e > p) lines.push_back(text.substr(p, e - p));
  }
  return lines;
}

}  // namespace

std::string sweep_id(const std::string& config_toml) { return hash_hex(text_hash(config_toml)); }

std::string task_path(const std::string& results_dir, const std::string& name) {
  return (std::filesystem::path(results_dir) / (name + ".h5")).string();
}

void write_task_file(const std::string& path, const std::string& id, const std::string& name, const std::string& status,
                     const std::string& reason, const TaskPayloadWriter* payload) {
  auto file = File::create(path);
  write_header(file, kTaskFormat, kTaskFormatVersion);
  write_attribute(file, "/", "sweep_id", id);
  write_attribute(file, "/", "task", name);
  write_attribute(file, "/", "status", status);
  write_attribute(file, "/", "reason", reason);
  if (payload) (*payload)(file, "/result");
  write_attribute(file, "/", "content_hash", hash_hex(content_hash(file, kTaskHashExclusions)));
  file.commit();
}

TaskRecord inspect_task(const std::string& path, const std::string& name, const std::string& id) {
  if (!std::filesystem::exists(path)) return {TaskState::missing, ""};
  try {
    auto file = File::open(path);
    check_header(file, kTaskFormat, kTaskFormatVersion);
    const std::string stored = read_string_attribute(file, "/", "content_hash");
    const std::string actual = hash_hex(content_hash(file, kTaskHashExclusions));
    if (stored != actual) return {TaskState::invalid, fmt::format("content hash {} != stored {}", actual, stored)};
    if (const std::string other = read_string_attribute(file, "/", "sweep_id"); other != id)
      return {TaskState::foreign, other};
    if (read_string_attribute(file, "/", "task") != name) return {TaskState::invalid, "holds another task"};
    const std::string status = read_string_attribute(file, "/", "status");
    if (status == "done") return {TaskState::done, ""};
    if (status == "failed") return {TaskState::failed, read_string_attribute(file, "/", "reason")};
    return {TaskState::invalid, "unknown status '" + status + "'"};
  } catch (const std::exception& e) {
    return {TaskState::invalid, e.what()};
  }
}

void write_sweep_status(File& file, const model::SweepStatus& s) {
  create_group(file, "/sweep");
  write_attribute(file, "/sweep", "sweep_id", s.sweep_id);
  write_attribute<std::uint32_t>(file, "/sweep", "tasks_total", s.tasks_total);
  write_attribute<std::uint32_t>(file, "/sweep", "n_failed", static_cast<std::uint32_t>(s.failed.size()));
  write_attribute<std::uint32_t>(file, "/sweep", "n_missing", static_cast<std::uint32_t>(s.missing.size()));
  write_attribute(file, "/sweep", "failed", join_lines(s.failed));
  write_attribute(file, "/sweep", "missing", join_lines(s.missing));
}

model::SweepStatus read_sweep_status(const File& file) {
  model::SweepStatus s;
  if (has_attribute(file, "/sweep", "sweep_id")) s.sweep_id = read_string_attribute(file, "/sweep", "sweep_id");
  s.tasks_total = read_attribute<std::uint32_t>(file, "/sweep", "tasks_total");
  s.failed = split_lines(read_string_attribute(file, "/sweep", "failed"));
  s.missing = split_lines(read_string_attribute(file, "/sweep", "missing"));
  if (s.failed.size() + s.missing.size() > s.tasks_total)
    throw InputError(fmt::format("{}: /sweep lists {} failed and {} missing of {} tasks", file.path(), s.failed.size(),
                                 s.missing.size(), s.tasks_total));
  return s;
}

}  // namespace clatter::io
