#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "mpi/cart.hpp"

using namespace clatter;

TEST(CartTopology, BlocksTileTheGridAndNeighboursAgree) {
  const int n = mpi::size(MPI_COMM_WORLD);
  mpi::CartTopology topo(MPI_COMM_WORLD, {30, 25, 20});
  const auto& d = topo.dims();
  EXPECT_EQ(d[0] * d[1] * d[2], n);
  const auto c = topo.local_count();
  long long cells = 1LL * c[0] * c[1] * c[2], total = 0;
  MPI_Allreduce(&cells, &total, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(total, 30LL * 25 * 20);
  // Every block must start where its lower neighbour ends.
  for (int axis = 0; axis < 3; ++axis) {
    const int lo = topo.neighbor(axis, -1), hi = topo.neighbor(axis, +1);
    int my_end = topo.local_start()[axis] + c[axis], lower_end = -1;
    MPI_Sendrecv(&my_end, 1, MPI_INT, hi, axis, &lower_end, 1, MPI_INT, lo, axis, topo.comm(), MPI_STATUS_IGNORE);
    if (lo == MPI_PROC_NULL) {
      EXPECT_EQ(topo.local_start()[axis], 0);
      EXPECT_EQ(topo.coords()[axis], 0);
    } else {
      EXPECT_EQ(lower_end, topo.local_start()[axis]) << "axis " << axis;
    }
    if (hi == MPI_PROC_NULL) {
      EXPECT_EQ(my_end, topo.global_cells()[axis]);
    }
  }
}

TEST(CartTopology, TooFewCellsIsAnInputError) {
  const int n = mpi::size(MPI_COMM_WORLD);
  if (n < 2) GTEST_SKIP() << "needs 2 or more ranks";
  EXPECT_THROW(mpi::CartTopology(MPI_COMM_WORLD, {1, 1, 1}), InputError);
}
