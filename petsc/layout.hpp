#pragma once
#include <mpi.h>
#include <petscsys.h>

#include <vector>

namespace clatter::petsc {

// How the rows (degrees of freedom) of a problem are spread over the ranks of a communicator:
// contiguous blocks, rank r owning [begin(r), end(r)). The same for every matrix and vector built
// on it. PETSc's own split (PetscLayout) unless the caller gives each rank's count.
class Layout {
 public:
  Layout(MPI_Comm comm, PetscInt global_size);                        // PETSc's even split
  Layout(MPI_Comm comm, PetscInt global_size, PetscInt local_size);  // collective: sizes must add up

  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  PetscInt global_size() const { return ranges_.back(); }
  PetscInt begin() const { return ranges_[rank_]; }
  PetscInt end() const { return ranges_[rank_ + 1]; }
  PetscInt local_size() const { return end() - begin(); }
  PetscInt begin(int rank) const { return ranges_[rank]; }
  PetscInt end(int rank) const { return ranges_[rank + 1]; }
  bool owns(PetscInt row) const { return row >= begin() && row < end(); }
  int owner(PetscInt row) const;  // rank owning `row`; throws for a row outside [0, global_size)
  // size + 1 entries: ranges()[r] is rank r's first row.
  const std::vector<PetscInt>& ranges() const { return ranges_; }

  bool operator==(const Layout& other) const;

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  std::vector<PetscInt> ranges_;
};

}  // namespace clatter::petsc
