#include <fmt/format.h>

#include <algorithm>

#include "core/stage_log.hpp"

namespace clatter {

std::string format_stage_table(const std::vector<StageStats>& rows, int n_ranks) {
  std::size_t name_width = 20;
  for (const auto& r : rows) {
    auto leaf = r.path.substr(r.path.rfind('/') + 1);  // npos + 1 == 0: whole path
    name_width = std::max(name_width, 2 * static_cast<std::size_t>(r.depth) + leaf.size());
  }
  const double total_s = rows.empty() ? 0.0 : rows.front().avg_s;
  std::string out = fmt::format("Stage timing (wall clock over {} rank{}; ratio = max/min):\n", n_ranks,
                                n_ranks == 1 ? "" : "s");
  std::string header = fmt::format("{:<{}}  {:>8}  {:>10}  {:>10}  {:>10}  {:>6}  {:>6}\n", "Stage", name_width,
                                   "Count", "Min [s]", "Avg [s]", "Max [s]", "Ratio", "%Total");
  out += header;
  out += std::string(header.size() - 1, '-') + '\n';
  for (const auto& r : rows) {
    auto leaf = r.path.substr(r.path.rfind('/') + 1);
    std::string name = std::string(2 * static_cast<std::size_t>(r.depth), ' ') + leaf;
    std::string ratio = r.min_s > 0 ? fmt::format("{:.2f}", r.max_s / r.min_s) : "-";
    std::string percent = total_s > 0 ? fmt::format("{:.1f}", 100.0 * r.avg_s / total_s) : "-";
    out += fmt::format("{:<{}}  {:>8}  {:>10.4e}  {:>10.4e}  {:>10.4e}  {:>6}  {:>6}\n", name, name_width, r.count,
                       r.min_s, r.avg_s, r.max_s, ratio, percent);
  }
  return out;
}

}  // namespace clatter
