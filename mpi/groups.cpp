#include "mpi/groups.hpp"

#include <string>

namespace clatter::mpi {

TaskGroups::TaskGroups(MPI_Comm comm, int ranks_per_group) {
  const int n = size(comm), me = rank(comm);
  if (ranks_per_group < 1 || n % ranks_per_group != 0)
    throw InputError("--ranks-per-task " + std::to_string(ranks_per_group) + " must be >= 1 and divide the " +
                     std::to_string(n) + " MPI ranks");
  group_index_ = me / ranks_per_group;
  n_groups_ = n / ranks_per_group;
  MPI_Comm group = MPI_COMM_NULL, leaders = MPI_COMM_NULL;
  check(MPI_Comm_split(comm, group_index_, me, &group), "MPI_Comm_split");
  group_ = OwnedComm(group);
  group_rank_ = rank(group);
  check(MPI_Comm_split(comm, group_rank_ == 0 ? 0 : MPI_UNDEFINED, me, &leaders), "MPI_Comm_split");
  leaders_ = OwnedComm(leaders);
}

}  // namespace clatter::mpi
