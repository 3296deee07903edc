#pragma once
#include <mpi.h>

#include "mpi/comm.hpp"

namespace clatter::mpi {

// Splits a communicator into equal groups of consecutive ranks, one group per concurrently running
// task (world rank r belongs to group r / ranks_per_group). The group roots share a second
// communicator, `leaders`, over which tasks are handed out and results collected.
class TaskGroups {
 public:
  // Throws InputError unless ranks_per_group >= 1 divides the communicator's size.
  TaskGroups(MPI_Comm comm, int ranks_per_group);

  MPI_Comm group() const { return group_.get(); }
  MPI_Comm leaders() const { return leaders_.get(); }  // MPI_COMM_NULL on non-root ranks of a group
  int group_index() const { return group_index_; }
  int n_groups() const { return n_groups_; }
  int group_rank() const { return group_rank_; }
  bool is_leader() const { return group_rank_ == 0; }

 private:
  OwnedComm group_;
  OwnedComm leaders_;
  int group_index_ = 0;
  int n_groups_ = 1;
  int group_rank_ = 0;
};

}  // namespace clatter::mpi
