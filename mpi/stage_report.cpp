#include "mpi/stage_report.hpp"

#include "mpi/comm.hpp"

namespace clatter::mpi {

std::string stage_table(MPI_Comm comm, const StageLog& log) {
  auto texts = gather(comm, serialize_stage_entries(log.entries()));
  if (texts.empty()) return {};
  std::vector<std::vector<StageLog::Entry>> per_rank;
  for (const auto& t : texts) per_rank.push_back(parse_stage_entries(t));
  return format_stage_table(merge_stage_entries(per_rank), size(comm));
}

}  // namespace clatter::mpi
