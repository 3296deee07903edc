#pragma once
// Counters that any rank advances without the others taking part: the slots live in an MPI window
// on rank 0 of the communicator, and each add is one atomic MPI_Fetch_and_op. A work queue uses
// it so that a group leader takes the next task index while the other groups are busy.
#include <mpi.h>

namespace clatter::mpi {

class SharedCounter {
 public:
  // Collective over `comm`: `slots` counters, all 0.
  SharedCounter(MPI_Comm comm, int slots);
  // Collective too (freeing the window): keep it alive until every rank is done with it.
  ~SharedCounter();
  SharedCounter(const SharedCounter&) = delete;
  SharedCounter& operator=(const SharedCounter&) = delete;

  // Adds `value` to counter `slot` atomically and returns the value before; add(slot, 0) reads it.
  // Not collective. std::out_of_range for a slot outside [0, slots).
  long long add(int slot, long long value);
  int slots() const { return slots_; }

 private:
  int slots_;
  long long* base_ = nullptr;
  MPI_Win win_ = MPI_WIN_NULL;
};

}  // namespace clatter::mpi
