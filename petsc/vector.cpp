#include "petsc/vector.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "petsc/error.hpp"

namespace clatter::petsc {

Vector::Vector(const Layout& layout) : layout_(layout) {
  check(VecCreateMPI(layout.comm(), layout.local_size(), layout.global_size(), &vec_), "VecCreateMPI");
  check(VecSet(vec_, 0.0), "VecSet");
}

Vector::Vector(const Layout& layout, std::span<const double> owned_values) : Vector(layout) {
  if (static_cast<PetscInt>(owned_values.size()) != layout.local_size())
    throw std::invalid_argument("Vector: " + std::to_string(owned_values.size()) + " values for " +
                                std::to_string(layout.local_size()) + " owned rows");
  PetscScalar* data = nullptr;
  check(VecGetArrayWrite(vec_, &data), "VecGetArrayWrite");
  std::copy(owned_values.begin(), owned_values.end(), data);
  check(VecRestoreArrayWrite(vec_, &data), "VecRestoreArrayWrite");
}

Vector::~Vector() {
  if (vec_) VecDestroy(&vec_);
}

Vector::Vector(Vector&& other) noexcept : layout_(other.layout_), vec_(std::exchange(other.vec_, nullptr)) {}

Vector& Vector::operator=(Vector&& other) noexcept {
  if (this != &other) {
    if (vec_) VecDestroy(&vec_);
    layout_ = other.layout_;
    vec_ = std::exchange(other.vec_, nullptr);
  }
  return *this;
}

std::vector<double> Vector::owned() const {
  const PetscScalar* data = nullptr;
  check(VecGetArrayRead(vec_, &data), "VecGetArrayRead");
  std::vector<double> values(data, data + layout_.local_size());
  check(VecRestoreArrayRead(vec_, &data), "VecRestoreArrayRead");
  return values;
}

std::vector<double> Vector::gather_to_root() const {
  VecScatter scatter = nullptr;
  Vec whole = nullptr;
  check(VecScatterCreateToZero(vec_, &scatter, &whole), "VecScatterCreateToZero");
  PetscErrorCode code = VecScatterBegin(scatter, vec_, whole, INSERT_VALUES, SCATTER_FORWARD);
  if (!code) code = VecScatterEnd(scatter, vec_, whole, INSERT_VALUES, SCATTER_FORWARD);
  std::vector<double> values;
  if (!code && layout_.rank() == 0) {
    const PetscScalar* data = nullptr;
    code = VecGetArrayRead(whole, &data);
    if (!code) {
      values.assign(data, data + layout_.global_size());
      code = VecRestoreArrayRead(whole, &data);
    }
  }
  VecScatterDestroy(&scatter);
  VecDestroy(&whole);
  check(code, "Vector::gather_to_root");
  return values;
}

}  // namespace clatter::petsc
