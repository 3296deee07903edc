// A binary of its own: a raised interrupt flag cannot be cleared, so it must not leak into
// other tests' process.
#include <gtest/gtest.h>

#include <csignal>
#include <string>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "mpi/comm.hpp"
#include "mpi/interrupt.hpp"

using namespace clatter;

TEST(InterruptPoll, EveryRankThrowsWhenOneRankWasSignalled) {
  const int me = mpi::rank(MPI_COMM_WORLD), n = mpi::size(MPI_COMM_WORLD);
  install_interrupt_handlers();
  EXPECT_FALSE(mpi::interrupt_seen(MPI_COMM_WORLD));
  EXPECT_NO_THROW(mpi::poll_interrupt(MPI_COMM_WORLD, "nothing"));
  // The handler only records the signal, as SIGTERM from Slurm would, on the last rank alone.
  if (me == n - 1) std::raise(SIGTERM);
  EXPECT_EQ(interrupt_requested(), me == n - 1);
  EXPECT_TRUE(mpi::interrupt_seen(MPI_COMM_WORLD));
  try {
    mpi::poll_interrupt(MPI_COMM_WORLD, "the test step");
    ADD_FAILURE() << "poll_interrupt did not throw on rank " << me;
  } catch (const Interrupted& e) {
    EXPECT_EQ(std::string(e.what()), "interrupted before the test step");
  }
}
