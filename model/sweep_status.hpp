#pragma once
// How complete the sweep that built a bank was (every bank kind built by sweep/sweep.hpp has one):
// the one definition io/ reads and writes as the bank's /sweep group (io/sweep_files.hpp).
#include <cstdint>
#include <string>
#include <vector>

namespace clatter::model {

struct SweepStatus {
  std::string sweep_id;               // hash of the sweep's config (io::sweep_id); banks of one sweep share it
  std::uint32_t tasks_total = 0;
  std::vector<std::string> failed;   // "task: reason"
  std::vector<std::string> missing;  // tasks never run (interrupted, not in this job's slice)

  std::uint32_t tasks_done() const {
    return tasks_total - static_cast<std::uint32_t>(failed.size() + missing.size());
  }
  bool complete() const { return failed.empty() && missing.empty(); }
};

}  // namespace clatter::model
