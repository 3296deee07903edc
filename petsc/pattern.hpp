#pragma once
#include <petscsys.h>

#include <cstddef>
#include <span>
#include <vector>

#include "petsc/layout.hpp"

namespace clatter::petsc {

// The nonzero pattern of a matrix assembled from square element blocks: for each row this rank
// owns, how many distinct columns fall inside its own column block (diagonal part) and outside
// (off-diagonal part) - PETSc's MPIAIJ preallocation, so assembly never reallocates.
// Built collectively from every rank's elements: rows owned elsewhere are sent to their owner.
// `dofs` holds `dofs_per_element` global indices per element; a negative index is a constrained
// degree of freedom (a Dirichlet end) that is left out, as MatSetValues leaves it out.
class Pattern {
 public:
  Pattern(const Layout& layout, std::span<const PetscInt> dofs, std::size_t dofs_per_element);

  const Layout& layout() const { return layout_; }
  std::size_t dofs_per_element() const { return dofs_per_element_; }
  const std::vector<PetscInt>& diagonal_counts() const { return diagonal_; }
  const std::vector<PetscInt>& off_diagonal_counts() const { return off_diagonal_; }
  // Nonzeros in this rank's rows.
  long long local_nonzeros() const;
  // The same on every rank for the same elements: two matrices on equal patterns share structure
  // (what SLEPc's K - sigma M update can exploit).
  unsigned long long fingerprint() const { return fingerprint_; }

 private:
  Layout layout_;
  std::size_t dofs_per_element_;
  std::vector<PetscInt> diagonal_, off_diagonal_;
  unsigned long long fingerprint_ = 0;
};

}  // namespace clatter::petsc
