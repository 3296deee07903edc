#pragma once
#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace clatter {

// Nested wall-clock stages in the manner of PETSc's -log_view. A stage entered while another is
// open becomes its child; an entry's path is "parent/child". Re-entering a stage adds to its time
// and call count. Not thread-safe: one log per process, used from the main thread.
class StageLog {
 public:
  struct Entry {
    std::string path;     // "total/field/write"
    int depth = 0;        // number of '/' in path
    long long count = 0;  // completed entries
    double seconds = 0;   // summed wall time of completed entries
  };

  std::size_t enter(std::string_view name);
  void leave(std::size_t index, double seconds);
  // A child of the innermost open stage timed by someone else (a library's own event log):
  // adds `count` calls and `seconds` to it without opening it.
  void add(std::string_view name, long long count, double seconds);
  const std::vector<Entry>& entries() const { return entries_; }
  bool empty() const { return entries_.empty(); }

 private:
  std::vector<Entry> entries_;
  std::vector<std::size_t> open_;
};

// The process-wide log that `--log-view` prints.
StageLog& stage_log();

// Times its own lifetime as one call of stage `name` (in `log`, by default the process-wide one).
class Stage {
 public:
  explicit Stage(std::string_view name, StageLog& log = stage_log());
  ~Stage();
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;
  double elapsed_s() const;

 private:
  using Clock = std::chrono::steady_clock;
  StageLog& log_;
  std::size_t index_;
  Clock::time_point start_;
};

// One row of the stage table: a stage's statistics over ranks.
struct StageStats {
  std::string path;
  int depth = 0;
  long long count = 0;  // largest call count over ranks
  double min_s = 0, avg_s = 0, max_s = 0;
};

// Merges the stage entries of every rank (index = rank) into table rows in tree order: each stage
// followed by its children, siblings in the order first seen (rank 0 first). A stage a rank never
// entered counts 0 s for that rank.
std::vector<StageStats> merge_stage_entries(const std::vector<std::vector<StageLog::Entry>>& per_rank);

// Serialises entries to one line per entry ("count\tseconds\tpath") and back, for gathering.
std::string serialize_stage_entries(const std::vector<StageLog::Entry>& entries);
std::vector<StageLog::Entry> parse_stage_entries(std::string_view text);

// The -log_view-like table. Percentages are of the first top-level row's average time.
std::string format_stage_table(const std::vector<StageStats>& rows, int n_ranks);

}  // namespace clatter
