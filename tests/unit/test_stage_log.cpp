#include <gtest/gtest.h>

#include "core/stage_log.hpp"

using clatter::Stage;
using clatter::StageLog;

TEST(StageLog, NestsAndCounts) {
  StageLog log;
  {
    Stage outer("solve", log);
    for (int i = 0; i < 3; ++i) Stage inner("step", log);
    Stage other("write", log);
  }
  { Stage again("solve", log); }
  const auto& e = log.entries();
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].path, "solve");
  EXPECT_EQ(e[0].count, 2);
  EXPECT_EQ(e[1].path, "solve/step");
  EXPECT_EQ(e[1].depth, 1);
  EXPECT_EQ(e[1].count, 3);
  EXPECT_EQ(e[2].path, "solve/write");
  EXPECT_GE(e[0].seconds, e[1].seconds + e[2].seconds);  // a parent includes its children
}

TEST(StageLog, AddRecordsATimedChildWithoutOpeningIt) {
  StageLog log;
  {
    Stage outer("solve", log);
    log.add("factor", 3, 0.25);
    log.add("factor", 2, 0.5);
    Stage inner("step", log);  // a sibling of "factor": add left nothing open
  }
  const auto& e = log.entries();
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[1].path, "solve/factor");
  EXPECT_EQ(e[1].count, 5);
  EXPECT_DOUBLE_EQ(e[1].seconds, 0.75);
  EXPECT_EQ(e[2].path, "solve/step");
}

TEST(StageLog, RejectsBadNamesAndOutOfOrderClose) {
  StageLog log;
  EXPECT_THROW(log.enter("a/b"), std::invalid_argument);
  EXPECT_THROW(log.enter(""), std::invalid_argument);
  auto a = log.enter("a");
  auto b = log.enter("b");
  EXPECT_THROW(log.leave(a, 0.0), std::logic_error);
  log.leave(b, 0.0);
  log.leave(a, 0.0);
}

TEST(StageLog, MergeGivesMinAvgMaxOverRanks) {
  using E = StageLog::Entry;
  std::vector<std::vector<E>> ranks = {
      {{"run", 0, 1, 4.0}, {"run/solve", 1, 10, 3.0}},
      {{"run", 0, 1, 6.0}, {"run/solve", 1, 12, 5.0}, {"run/io", 1, 2, 1.0}},
  };
  auto rows = clatter::merge_stage_entries(ranks);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].path, "run");
  EXPECT_DOUBLE_EQ(rows[0].min_s, 4.0);
  EXPECT_DOUBLE_EQ(rows[0].avg_s, 5.0);
  EXPECT_DOUBLE_EQ(rows[0].max_s, 6.0);
  EXPECT_EQ(rows[1].path, "run/solve");
  EXPECT_EQ(rows[1].count, 12);
  EXPECT_EQ(rows[2].path, "run/io");
  EXPECT_DOUBLE_EQ(rows[2].min_s, 0.0);  // rank 0 never entered it
  EXPECT_DOUBLE_EQ(rows[2].avg_s, 0.5);
}

TEST(StageLog, ChildrenFollowTheirParentWhateverTheRankOrder) {
  using E = StageLog::Entry;
  std::vector<std::vector<E>> ranks = {{{"a", 0, 1, 1}, {"b", 0, 1, 1}}, {{"a", 0, 1, 1}, {"b", 0, 1, 1}, {"a/x", 1, 1, 1}}};
  auto rows = clatter::merge_stage_entries(ranks);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].path, "a/x");
}

TEST(StageLog, SerializationRoundTripsExactly) {
  std::vector<StageLog::Entry> e = {{"total", 0, 3, 0.1 + 0.2}, {"total/a b", 1, 1, 1e-9 / 3}};
  auto back = clatter::parse_stage_entries(clatter::serialize_stage_entries(e));
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < e.size(); ++i) {
    EXPECT_EQ(back[i].path, e[i].path);
    EXPECT_EQ(back[i].depth, e[i].depth);
    EXPECT_EQ(back[i].count, e[i].count);
    EXPECT_EQ(back[i].seconds, e[i].seconds);
  }
}

TEST(StageLog, TableIndentsChildrenAndShowsPercentages) {
  std::vector<clatter::StageStats> rows = {{"run", 0, 1, 2.0, 2.0, 2.0}, {"run/solve", 1, 5, 1.0, 1.5, 2.0}};
  auto table = clatter::format_stage_table(rows, 2);
  EXPECT_NE(table.find("over 2 ranks"), std::string::npos);
  EXPECT_NE(table.find("\n  solve "), std::string::npos);
  EXPECT_NE(table.find("75.0"), std::string::npos);  // 1.5 s of 2 s
  EXPECT_NE(table.find("2.00"), std::string::npos);  // max/min ratio
}
