#include <gtest/gtest.h>

#include <cstdio>

#include "mpi/comm.hpp"
#include "mpi/stage_report.hpp"

using namespace clatter;

TEST(StageReport, GathersEveryRanksStages) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  StageLog log;
  // Fake times make min/avg/max exact: rank r spends r + 1 seconds in "work" and calls it r + 1 times.
  auto run = log.enter("run");
  auto work = log.enter("work");
  log.leave(work, me + 1.0);
  for (int i = 0; i < me; ++i) log.leave(log.enter("work"), 0.0);
  if (me == n - 1) log.leave(log.enter("only_last"), 0.5);
  log.leave(run, 10.0);
  auto table = mpi::stage_table(MPI_COMM_WORLD, log);
  if (me != 0) {
    EXPECT_TRUE(table.empty());
    return;
  }
  auto row = [&](const std::string& name) {
    std::string needle = "\n  ";  // a child row: two spaces of indent, then the name
    needle.append(name).append(" ");
    auto pos = table.find(needle);
    EXPECT_NE(pos, std::string::npos) << table;
    return table.substr(pos + 1, table.find('\n', pos + 1) - pos - 1);
  };
  const std::string work_row = row("work");
  char count_text[32];
  std::snprintf(count_text, sizeof count_text, " %d ", n);  // max count
  EXPECT_NE(work_row.find(count_text), std::string::npos) << work_row;
  EXPECT_NE(work_row.find("1.0000e+00"), std::string::npos) << work_row;                     // min
  char max_text[32];
  std::snprintf(max_text, sizeof max_text, "%.4e", double(n));  // max = n seconds
  EXPECT_NE(work_row.find(max_text), std::string::npos) << work_row;
  row("only_last");
}
