#include "petsc/matrix.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "core/stage_log.hpp"
#include "petsc/error.hpp"

namespace clatter::petsc {

Matrix::Matrix(const Pattern& pattern) : layout_(pattern.layout()), fingerprint_(pattern.fingerprint()) {
  const PetscInt n_local = layout_.local_size();
  check(MatCreate(layout_.comm(), &mat_), "MatCreate");
  check(MatSetSizes(mat_, n_local, n_local, layout_.global_size(), layout_.global_size()), "MatSetSizes");
  check(MatSetType(mat_, MATAIJ), "MatSetType");
  // Only the call matching the matrix's actual type (Seq or MPI) takes effect.
  check(MatSeqAIJSetPreallocation(mat_, 0, pattern.diagonal_counts().data()), "MatSeqAIJSetPreallocation");
  check(MatMPIAIJSetPreallocation(mat_, 0, pattern.diagonal_counts().data(), 0, pattern.off_diagonal_counts().data()),
        "MatMPIAIJSetPreallocation");
  check(MatSetOption(mat_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
  check(MatSetOption(mat_, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
}

Matrix::~Matrix() {
  if (mat_) MatDestroy(&mat_);
}

Matrix::Matrix(Matrix&& other) noexcept
    : layout_(other.layout_),
      fingerprint_(other.fingerprint_),
      mat_(std::exchange(other.mat_, nullptr)),
      assembled_(other.assembled_) {}

Matrix& Matrix::operator=(Matrix&& other) noexcept {
  if (this != &other) {
    if (mat_) MatDestroy(&mat_);
    layout_ = other.layout_;
    fingerprint_ = other.fingerprint_;
    mat_ = std::exchange(other.mat_, nullptr);
    assembled_ = other.assembled_;
  }
  return *this;
}

void Matrix::add_element(std::span<const PetscInt> dofs, std::span<const double> block) {
  if (block.size() != dofs.size() * dofs.size())
    throw std::invalid_argument("Matrix::add_element: " + std::to_string(dofs.size()) + " indices need " +
                                std::to_string(dofs.size() * dofs.size()) + " values, got " +
                                std::to_string(block.size()));
  const auto n = static_cast<PetscInt>(dofs.size());
  check(MatSetValues(mat_, n, dofs.data(), n, dofs.data(), block.data(), ADD_VALUES), "MatSetValues");
  assembled_ = false;
}

void Matrix::assemble() {
  Stage stage("assembly");
  check(MatAssemblyBegin(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(mat_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  assembled_ = true;
}

Matrix assemble_elements(const Pattern& pattern, std::span<const PetscInt> dofs, std::span<const double> blocks) {
  Stage stage("assembly");
  const std::size_t k = pattern.dofs_per_element();
  if (dofs.size() % k != 0 || blocks.size() != dofs.size() / k * k * k)
    throw std::invalid_argument("assemble_elements: " + std::to_string(dofs.size()) + " indices and " +
                                std::to_string(blocks.size()) + " values are not whole elements of " +
                                std::to_string(k));
  Matrix matrix(pattern);
  for (std::size_t e = 0; e < dofs.size() / k; ++e) matrix.add_element(dofs.subspan(e * k, k), blocks.subspan(e * k * k, k * k));
  matrix.assemble();
  return matrix;
}

}  // namespace clatter::petsc
