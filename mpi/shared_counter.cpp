#include "mpi/shared_counter.hpp"

#include <stdexcept>
#include <string>

#include "mpi/comm.hpp"

namespace clatter::mpi {

SharedCounter::SharedCounter(MPI_Comm comm, int slots) : slots_(slots) {
  if (slots < 1) throw std::invalid_argument("SharedCounter: needs at least one slot");
  const bool root = rank(comm) == 0;
  const MPI_Aint bytes = root ? static_cast<MPI_Aint>(slots) * static_cast<MPI_Aint>(sizeof(long long)) : 0;
  check(MPI_Win_allocate(bytes, sizeof(long long), MPI_INFO_NULL, comm, &base_, &win_), "MPI_Win_allocate");
  if (root) {
    // The window's memory is only ours to write inside an epoch.
    MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, win_);
    for (int i = 0; i < slots; ++i) base_[i] = 0;
    MPI_Win_unlock(0, win_);
  }
  // Nobody adds before root has zeroed the slots.
  check(MPI_Barrier(comm), "MPI_Barrier");
  check(MPI_Win_lock_all(0, win_), "MPI_Win_lock_all");
}

SharedCounter::~SharedCounter() {
  MPI_Win_unlock_all(win_);
  MPI_Win_free(&win_);
}

long long SharedCounter::add(int slot, long long value) {
  if (slot < 0 || slot >= slots_)
    throw std::out_of_range("SharedCounter: slot " + std::to_string(slot) + " of " + std::to_string(slots_));
  long long before = 0;
  check(MPI_Fetch_and_op(&value, &before, MPI_LONG_LONG, 0, slot, MPI_SUM, win_), "MPI_Fetch_and_op");
  // The result is only defined once the operation is complete at the target.
  check(MPI_Win_flush(0, win_), "MPI_Win_flush");
  return before;
}

}  // namespace clatter::mpi
