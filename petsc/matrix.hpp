#pragma once
#include <petscmat.h>

#include <span>

#include "petsc/layout.hpp"
#include "petsc/pattern.hpp"

namespace clatter::petsc {

// A square distributed sparse matrix (MATAIJ: SeqAIJ on one rank, MPIAIJ on more) preallocated
// from a Pattern, filled by adding element blocks, then assembled. Inserting outside the pattern
// is an error rather than a silent reallocation. Rows follow the pattern's Layout.
class Matrix {
 public:
  explicit Matrix(const Pattern& pattern);
  ~Matrix();
  Matrix(Matrix&& other) noexcept;
  Matrix& operator=(Matrix&& other) noexcept;
  Matrix(const Matrix&) = delete;
  Matrix& operator=(const Matrix&) = delete;

  // Adds a dense row-major block (dofs.size()^2 values) at the global indices `dofs`; negative
  // indices are skipped (constrained). Any rank may add to any row.
  void add_element(std::span<const PetscInt> dofs, std::span<const double> block);
  // Collective: sends the blocks added to other ranks' rows, timed as stage "assembly".
  void assemble();

  Mat get() const { return mat_; }
  const Layout& layout() const { return layout_; }
  unsigned long long pattern_fingerprint() const { return fingerprint_; }
  bool assembled() const { return assembled_; }

 private:
  Layout layout_;
  unsigned long long fingerprint_ = 0;
  Mat mat_ = nullptr;
  bool assembled_ = false;
};

// add_element for every element of `dofs` (dofs_per_element each, as in Pattern) with its block
// in `blocks` (dofs_per_element^2 values each, row-major), then assemble(); the whole of it is
// stage "assembly".
Matrix assemble_elements(const Pattern& pattern, std::span<const PetscInt> dofs, std::span<const double> blocks);

}  // namespace clatter::petsc
