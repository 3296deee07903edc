#include <gtest/gtest.h>

#include <array>
#include <complex>
#include <cstdint>
#include <set>
#include <vector>

#include "mpi/collectives.hpp"
#include "mpi/shared_counter.hpp"

using namespace clatter;

namespace {
struct Record {  // padding between the members on purpose: it travels as bytes
  std::uint64_t id = 0;
  std::int32_t order = 0;
  double value = 0;
  std::array<float, 3> xyz{};
};
}  // namespace

TEST(Collectives, BroadcastsValuesAndStructs) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  EXPECT_EQ(mpi::broadcast(MPI_COMM_WORLD, me == 0 ? 42LL : -1LL), 42LL);
  EXPECT_EQ(mpi::broadcast(MPI_COMM_WORLD, me == n - 1 ? 2.5 : 0.0, n - 1), 2.5);
  const Record sent{7, -3, 0.125, {1.f, 2.f, 3.f}};
  const Record got = mpi::broadcast(MPI_COMM_WORLD, me == 0 ? sent : Record{});
  EXPECT_EQ(got.id, 7u);
  EXPECT_EQ(got.order, -3);
  EXPECT_EQ(got.value, 0.125);
  EXPECT_EQ(got.xyz, sent.xyz);
}

TEST(Collectives, BroadcastsVectorsWhateverTheOthersHold) {
  const int me = mpi::rank(MPI_COMM_WORLD);
  const std::vector<std::complex<double>> values{{1, -1}, {0.5, 2}, {-3, 0}};
  auto got = mpi::broadcast(MPI_COMM_WORLD, me == 0 ? values : std::vector<std::complex<double>>(5, {9, 9}));
  EXPECT_EQ(got, values);
  // An empty vector empties the others' too.
  EXPECT_TRUE(mpi::broadcast(MPI_COMM_WORLD, me == 0 ? std::vector<int>{} : std::vector<int>{1, 2}).empty());
  const std::vector<std::array<std::int32_t, 6>> faces{{0, 1, 2, 3, 4, 5}, {6, 7, 8, 9, 10, 11}};
  EXPECT_EQ(mpi::broadcast(MPI_COMM_WORLD, me == 0 ? faces : decltype(faces){}), faces);
}

TEST(Collectives, GathersValuesToRoot) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  const auto all = mpi::gather(MPI_COMM_WORLD, Record{static_cast<std::uint64_t>(me), me * 10, me + 0.5, {}});
  if (me != 0) {
    EXPECT_TRUE(all.empty());
    return;
  }
  ASSERT_EQ(all.size(), static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) {
    EXPECT_EQ(all[r].id, static_cast<std::uint64_t>(r));
    EXPECT_EQ(all[r].order, r * 10);
    EXPECT_EQ(all[r].value, r + 0.5);
  }
}

TEST(Collectives, GathersVectorsOfDifferentLengths) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  // Rank r sends r values r, r+1, ...: rank 0 sends an empty vector.
  std::vector<double> mine;
  for (int i = 0; i < me; ++i) mine.push_back(me + i);
  const int root = n - 1;
  const auto all = mpi::gather(MPI_COMM_WORLD, mine, root);
  if (me != root) {
    EXPECT_TRUE(all.empty());
  } else {
    ASSERT_EQ(all.size(), static_cast<std::size_t>(n));
    for (int r = 0; r < n; ++r) {
      ASSERT_EQ(all[r].size(), static_cast<std::size_t>(r));
      for (int i = 0; i < r; ++i) EXPECT_EQ(all[r][i], r + i);
    }
  }
  // Nobody sends anything.
  const auto none = mpi::gather(MPI_COMM_WORLD, std::vector<Record>{});
  if (me == 0) {
    ASSERT_EQ(none.size(), static_cast<std::size_t>(n));
    for (const auto& v : none) EXPECT_TRUE(v.empty());
  }
}

TEST(Collectives, AllGathersAndReduces) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  const auto ranks = mpi::all_gather(MPI_COMM_WORLD, me);
  ASSERT_EQ(ranks.size(), static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) EXPECT_EQ(ranks[r], r);
  EXPECT_EQ(mpi::all_reduce_sum(MPI_COMM_WORLD, me + 1), n * (n + 1) / 2);
  EXPECT_EQ(mpi::all_reduce_max(MPI_COMM_WORLD, 0.5 * me), 0.5 * (n - 1));
  EXPECT_EQ(mpi::all_reduce_min(MPI_COMM_WORLD, static_cast<std::uint64_t>(me + 3)), 3u);
  const std::array<long long, 2> sums = mpi::all_reduce_sum(MPI_COMM_WORLD, std::array<long long, 2>{1, me});
  EXPECT_EQ(sums[0], n);
  EXPECT_EQ(sums[1], static_cast<long long>(n) * (n - 1) / 2);
  const auto maxes = mpi::all_reduce_max(MPI_COMM_WORLD, std::array<int, 2>{me, -me});
  EXPECT_EQ(maxes[0], n - 1);
  EXPECT_EQ(maxes[1], 0);
  const auto vector_sum = mpi::all_reduce_sum(MPI_COMM_WORLD, std::vector<float>{1.f, static_cast<float>(me)});
  EXPECT_EQ(vector_sum, (std::vector<float>{static_cast<float>(n), static_cast<float>(n * (n - 1) / 2)}));
}

TEST(Collectives, AnyIsALogicalOrOverRanks) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  EXPECT_FALSE(mpi::any(MPI_COMM_WORLD, false));
  EXPECT_TRUE(mpi::any(MPI_COMM_WORLD, true));
  EXPECT_TRUE(mpi::any(MPI_COMM_WORLD, me == n - 1));
}

TEST(Collectives, RefusesCountsPastIntMax) {
  EXPECT_THROW(mpi::detail::byte_count(static_cast<std::uint64_t>(INT_MAX) / 8 + 1, 8, "test"), std::length_error);
  EXPECT_EQ(mpi::detail::byte_count(static_cast<std::uint64_t>(INT_MAX) / 8, 8, "test"), INT_MAX / 8 * 8);
}

TEST(SharedCounter, HandsOutEveryIndexExactlyOnce) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  constexpr long long kItems = 200;
  std::vector<long long> mine;
  {
    mpi::SharedCounter counter(MPI_COMM_WORLD, 2);
    EXPECT_EQ(counter.slots(), 2);
    EXPECT_THROW(counter.add(2, 1), std::out_of_range);
    for (long long i; (i = counter.add(0, 1)) < kItems;) {
      mine.push_back(i);
      counter.add(1, 10);
    }
    MPI_Barrier(MPI_COMM_WORLD);  // every add is done before anyone reads the totals
    // Every rank overshot the end by exactly one take.
    EXPECT_EQ(counter.add(0, 0), kItems + n);
    EXPECT_EQ(counter.add(1, 0), 10 * kItems);
    MPI_Barrier(MPI_COMM_WORLD);
  }
  const auto all = mpi::gather(MPI_COMM_WORLD, mine);
  if (me != 0) return;
  std::multiset<long long> seen;
  for (const auto& v : all) seen.insert(v.begin(), v.end());
  ASSERT_EQ(seen.size(), static_cast<std::size_t>(kItems));
  long long expect = 0;
  for (const long long i : seen) EXPECT_EQ(i, expect++);
}
