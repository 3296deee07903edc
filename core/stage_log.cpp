#include "core/stage_log.hpp"

#include <algorithm>
#include <charconv>
#include <map>
#include <stdexcept>

namespace clatter {

std::size_t StageLog::enter(std::string_view name) {
  if (name.empty() || name.find_first_of("/\t\n") != std::string_view::npos)
    throw std::invalid_argument("stage name must be non-empty without '/', tab or newline: '" +
                                std::string(name) + "'");
  std::string path = open_.empty() ? std::string(name) : entries_[open_.back()].path + "/" + std::string(name);
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.path == path; });
  std::size_t index = static_cast<std::size_t>(it - entries_.begin());
  if (it == entries_.end()) {
    entries_.push_back({path, static_cast<int>(open_.size()), 0, 0.0});
  }
  open_.push_back(index);
  return index;
}

void StageLog::leave(std::size_t index, double seconds) {
  // Stages are scoped objects, so they close in reverse order of opening.
  if (open_.empty() || open_.back() != index) throw std::logic_error("stage closed out of order");
  open_.pop_back();
  entries_[index].count += 1;
  entries_[index].seconds += seconds;
}

void StageLog::add(std::string_view name, long long count, double seconds) {
  const std::size_t index = enter(name);
  open_.pop_back();
  entries_[index].count += count;
  entries_[index].seconds += seconds;
}

StageLog& stage_log() {
  static StageLog log;
  return log;
}

Stage::Stage(std::string_view name, StageLog& log) : log_(log), index_(log.enter(name)), start_(Clock::now()) {}

Stage::~Stage() { log_.leave(index_, elapsed_s()); }

double Stage::elapsed_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

std::vector<StageStats> merge_stage_entries(const std::vector<std::vector<StageLog::Entry>>& per_rank) {
  // Tree of paths in first-seen order, then a depth-first walk.
  std::vector<std::string> order;
  std::map<std::string, std::vector<std::string>> children;  // parent path ("" = root) -> child paths
  std::map<std::string, StageStats> stats;
  const double n_ranks = static_cast<double>(std::max<std::size_t>(per_rank.size(), 1));
  for (const auto& entries : per_rank) {
    for (const auto& e : entries) {
      auto [it, inserted] = stats.try_emplace(e.path);
      StageStats& s = it->second;
      if (inserted) {
        s.path = e.path;
        s.depth = e.depth;
        s.min_s = e.seconds;
        s.max_s = e.seconds;
        auto slash = e.path.rfind('/');
        children[slash == std::string::npos ? "" : e.path.substr(0, slash)].push_back(e.path);
      }
      s.count = std::max(s.count, e.count);
      s.min_s = std::min(s.min_s, e.seconds);
      s.max_s = std::max(s.max_s, e.seconds);
      s.avg_s += e.seconds / n_ranks;
    }
  }
  // A rank that never entered a stage spent 0 s in it.
  for (auto& [path, s] : stats) {
    std::size_t seen = 0;
    for (const auto& entries : per_rank)
      // An init-capture: clang 14 (the fuzz preset) cannot capture a structured binding.
      seen += std::count_if(entries.begin(), entries.end(), [&name = path](const auto& e) { return e.path == name; }) > 0;
    if (seen < per_rank.size()) s.min_s = 0;
  }
  std::vector<StageStats> rows;
  auto walk = [&](auto&& self, const std::string& parent) -> void {
    auto it = children.find(parent);
    if (it == children.end()) return;
    for (const auto& child : it->second) {
      rows.push_back(stats[child]);
      self(self, child);
    }
  };
  walk(walk, "");
  return rows;
}

std::string serialize_stage_entries(const std::vector<StageLog::Entry>& entries) {
  std::string text;
  for (const auto& e : entries) {
    text += std::to_string(e.count) + '\t';
    char buf[64];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, e.seconds);  // shortest round-trip form
    text.append(buf, end);
    text += '\t' + e.path + '\n';
  }
  return text;
}

std::vector<StageLog::Entry> parse_stage_entries(std::string_view text) {
  std::vector<StageLog::Entry> entries;
  while (!text.empty()) {
    auto eol = text.find('\n');
    std::string_view line = text.substr(0, eol);
    text = eol == std::string_view::npos ? std::string_view{} : text.substr(eol + 1);
    auto t1 = line.find('\t'), t2 = line.find('\t', t1 + 1);
    if (t1 == std::string_view::npos || t2 == std::string_view::npos)
      throw std::runtime_error("malformed stage record: '" + std::string(line) + "'");
    StageLog::Entry e;
    std::from_chars(line.data(), line.data() + t1, e.count);
    std::from_chars(line.data() + t1 + 1, line.data() + t2, e.seconds);
    e.path = std::string(line.substr(t2 + 1));
    e.depth = static_cast<int>(std::count(e.path.begin(), e.path.end(), '/'));
    entries.push_back(std::move(e));
  }
  return entries;
}

}  // namespace clatter
