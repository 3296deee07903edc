#include "petsc/layout.hpp"

#include <petscis.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "petsc/error.hpp"

namespace clatter::petsc {

Layout::Layout(MPI_Comm comm, PetscInt global_size) : Layout(comm, global_size, PETSC_DECIDE) {}

Layout::Layout(MPI_Comm comm, PetscInt global_size, PetscInt local_size) : comm_(comm) {
  if (global_size < 0) throw std::invalid_argument("Layout: negative global size " + std::to_string(global_size));
  MPI_Comm_rank(comm, &rank_);
  PetscLayout layout = nullptr;
  check(PetscLayoutCreate(comm, &layout), "PetscLayoutCreate");
  PetscErrorCode code = PetscLayoutSetLocalSize(layout, local_size);
  if (!code) code = PetscLayoutSetSize(layout, global_size);
  if (!code) code = PetscLayoutSetUp(layout);
  const PetscInt* ranges = nullptr;
  if (!code) code = PetscLayoutGetRanges(layout, &ranges);
  if (!code) {
    int size = 1;
    MPI_Comm_size(comm, &size);
    ranges_.assign(ranges, ranges + size + 1);
  }
  PetscLayoutDestroy(&layout);
  check(code, "PetscLayout");
}

int Layout::owner(PetscInt row) const {
  if (row < 0 || row >= global_size())
    throw std::out_of_range("Layout: row " + std::to_string(row) + " outside [0, " + std::to_string(global_size()) + ")");
  auto it = std::upper_bound(ranges_.begin(), ranges_.end(), row);
  return static_cast<int>(it - ranges_.begin()) - 1;
}

bool Layout::operator==(const Layout& other) const {
  int same = 0;
  MPI_Comm_compare(comm_, other.comm_, &same);
  return (same == MPI_IDENT || same == MPI_CONGRUENT) && ranges_ == other.ranges_;
}

}  // namespace clatter::petsc
