// How compute_modal_transfer (banks/modal/modal_transfer.hpp) hands an entry's modes to the ranks
// of its group, with a stand-in for the per-mode solve that reports which rank ran which mode:
//  - every mode is solved exactly once and lands at its own index, whatever rank took it;
//  - the modes go out as a queue, highest first: while one rank is held up by the top mode, the
//    others take every other mode (in rounds of one mode per rank they would wait for it);
//  - a mode that throws fails the task on every rank with the mode named;
//  - an interrupt on one rank stops every rank once its current mode is done (tests/CMakeLists.txt
//    runs that one in a process of its own: a raised interrupt flag stays raised).
#include <gtest/gtest.h>
#include <mpi.h>

#include <chrono>
#include <complex>
#include <csignal>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "banks/modal/modal_transfer.hpp"
#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "mpi/collectives.hpp"
#include "mpi/comm.hpp"

namespace {
using namespace clatter;
namespace kt = kernels::transfer;

// An entry of `n` modes with nothing but frequencies: the stand-in solves read no surface.
model::ModalEntry entry_of(std::size_t n) {
  model::ModalEntry e;
  e.axes_m = {0.3, 0.5, 0.8};
  for (std::size_t i = 0; i < n; ++i) e.frequencies_hz.push_back(1000.0 + 10.0 * static_cast<double>(i));
  return e;
}

// A mode's stand-in transfer: its index and its rank in the coefficient, its index as the order.
kt::ModeTransfer stand_in(std::size_t mode, int rank) {
  kt::ModeTransfer t;
  t.expansion.coefficients = {std::complex<double>(static_cast<double>(mode), rank)};
  t.expansion.order = static_cast<int>(mode);
  return t;
}

TEST(TransferQueue, EveryModeOnceInModeOrderAndTheTopModeDoesNotHoldUpTheRest) {
  const int me = mpi::rank(MPI_COMM_WORLD), ranks = mpi::size(MPI_COMM_WORLD);
  constexpr std::size_t n = 23;
  auto entry = entry_of(n);
  long long solved_here = 0;
  const jobs::ModeTransferSolver solve = [&](const model::ModalEntry&, std::size_t mode) {
    ++solved_here;
    // The top mode is handed out first and takes far longer than all the others together take
    // to hand out (microseconds each).
    if (mode == n - 1) std::this_thread::sleep_for(std::chrono::milliseconds(500));
    return stand_in(mode, me);
  };
  jobs::compute_modal_transfer(MPI_COMM_WORLD, solve, entry);
  EXPECT_EQ(mpi::all_reduce_sum(MPI_COMM_WORLD, solved_here), static_cast<long long>(n));
  if (me != 0) return;
  const auto& t = entry.transfer;
  ASSERT_EQ(t.order.size(), n);
  ASSERT_EQ(t.coefficients.size(), 2 * n);  // (re, im) per mode
  std::vector<int> rank_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(t.order[i], static_cast<int>(i));
    EXPECT_EQ(t.coefficients[2 * i], static_cast<double>(i));
    rank_of[i] = static_cast<int>(t.coefficients[2 * i + 1]);
  }
  if (ranks > 1) {
    // The rank that held the top mode solved nothing else: the others took every other mode.
    for (std::size_t i = 0; i + 1 < n; ++i) EXPECT_NE(rank_of[i], rank_of[n - 1]) << "mode " << i;
  }
  EXPECT_GT(entry.cost.transfer_core_s, 0.0);
}

TEST(TransferQueue, AModeThatThrowsFailsTheTaskOnEveryRank) {
  constexpr std::size_t n = 9, bad = 4;
  auto entry = entry_of(n);
  const jobs::ModeTransferSolver solve = [&](const model::ModalEntry&, std::size_t mode) {
    if (mode == bad) throw std::runtime_error("zgels failed");
    return stand_in(mode, 0);
  };
  try {
    jobs::compute_modal_transfer(MPI_COMM_WORLD, solve, entry);
    ADD_FAILURE() << "no TaskFailure";
  } catch (const TaskFailure& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mode 4 (1040.0 Hz)"), std::string::npos) << what;
    EXPECT_NE(what.find("zgels failed"), std::string::npos) << what;
  }
  // Every rank is back in step: a collective after the failure completes.
  EXPECT_EQ(mpi::all_reduce_sum(MPI_COMM_WORLD, 1LL), static_cast<long long>(mpi::size(MPI_COMM_WORLD)));
}

// In a process of its own (--gtest_filter=TransferQueueInterrupt.*).
TEST(TransferQueueInterrupt, OneRankSignalledStopsEveryRankWithinAMode) {
  const int me = mpi::rank(MPI_COMM_WORLD), last = mpi::size(MPI_COMM_WORLD) - 1;
  install_interrupt_handlers();
  ASSERT_FALSE(interrupt_requested());
  constexpr std::size_t n = 200;
  auto entry = entry_of(n);
  long long solved_here = 0;
  const jobs::ModeTransferSolver solve = [&](const model::ModalEntry&, std::size_t mode) {
    ++solved_here;
    // As SIGTERM from Slurm would, on the last rank alone, during its first mode.
    if (me == last && solved_here == 1) std::raise(SIGTERM);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return stand_in(mode, me);
  };
  bool interrupted = false;
  try {
    jobs::compute_modal_transfer(MPI_COMM_WORLD, solve, entry);
  } catch (const Interrupted&) {
    interrupted = true;
  }
  EXPECT_TRUE(interrupted) << "rank " << me;
  // The signalled rank took no mode after it; the others finished the one they held (and at most
  // the ones they took before the queue was emptied, a few 20-ms modes): far from all 200.
  if (me == last) {
    EXPECT_EQ(solved_here, 1);
  }
  EXPECT_LT(mpi::all_reduce_sum(MPI_COMM_WORLD, solved_here), static_cast<long long>(n) / 4);
}

}  // namespace
