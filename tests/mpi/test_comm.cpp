#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "mpi/comm.hpp"
#include "mpi/groups.hpp"

using namespace clatter;

TEST(Comm, BroadcastAndGatherStrings) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  EXPECT_EQ(mpi::broadcast(MPI_COMM_WORLD, me == 0 ? std::string("from rank 0\n\0x", 14) : std::string()),
            std::string("from rank 0\n\0x", 14));
  auto all = mpi::gather(MPI_COMM_WORLD, std::string(static_cast<std::size_t>(me), 'a' + char(me % 26)));
  if (me == 0) {
    ASSERT_EQ(all.size(), static_cast<std::size_t>(n));
    for (int r = 0; r < n; ++r) EXPECT_EQ(all[r], std::string(static_cast<std::size_t>(r), 'a' + char(r % 26)));
  } else {
    EXPECT_TRUE(all.empty());
  }
}

TEST(Comm, AgreeSharesTheLowestFailingRanksError) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  EXPECT_NO_THROW(mpi::agree(MPI_COMM_WORLD, [] {}));
  // Fails on the last rank only: every rank must leave with its message and the input-error code.
  try {
    mpi::agree(MPI_COMM_WORLD, [&] {
      if (me == n - 1) throw InputError("bad value on rank " + std::to_string(me));
    });
    ADD_FAILURE() << "agree did not throw";
  } catch (const mpi::CollectiveError& e) {
    EXPECT_EQ(std::string(e.what()), "bad value on rank " + std::to_string(n - 1));
    EXPECT_EQ(e.exit_code(), kExitInputError);
  }
  // Several ranks fail: the lowest speaks; a non-input error maps to the failure code.
  try {
    mpi::agree(MPI_COMM_WORLD, [&] { throw std::runtime_error("rank " + std::to_string(me)); });
    ADD_FAILURE() << "agree did not throw";
  } catch (const mpi::CollectiveError& e) {
    EXPECT_EQ(std::string(e.what()), "rank 0");
    EXPECT_EQ(e.exit_code(), kExitFailure);
  }
}

TEST(TaskGroups, SplitsIntoEqualGroupsWithLeaders) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  for (int per = 1; per <= n; ++per) {
    if (n % per != 0) {
      EXPECT_THROW(mpi::TaskGroups(MPI_COMM_WORLD, per), InputError);
      continue;
    }
    mpi::TaskGroups groups(MPI_COMM_WORLD, per);
    EXPECT_EQ(groups.n_groups(), n / per);
    EXPECT_EQ(groups.group_index(), me / per);
    EXPECT_EQ(groups.group_rank(), me % per);
    EXPECT_EQ(mpi::size(groups.group()), per);
    // The group's world ranks are consecutive: their sum is known in closed form.
    int sum = 0;
    MPI_Allreduce(&me, &sum, 1, MPI_INT, MPI_SUM, groups.group());
    const int first = groups.group_index() * per;
    EXPECT_EQ(sum, per * first + per * (per - 1) / 2);
    EXPECT_EQ(groups.leaders() != MPI_COMM_NULL, groups.is_leader());
    if (groups.is_leader()) {
      EXPECT_EQ(mpi::size(groups.leaders()), n / per);
    }
  }
  EXPECT_THROW(mpi::TaskGroups(MPI_COMM_WORLD, 0), InputError);
}
