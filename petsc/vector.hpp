#pragma once
#include <petscvec.h>

#include <span>
#include <vector>

#include "petsc/layout.hpp"

namespace clatter::petsc {

// A distributed vector on a Layout (each rank holds its rows).
class Vector {
 public:
  explicit Vector(const Layout& layout);  // zeros
  // This rank's rows, layout.local_size() values.
  Vector(const Layout& layout, std::span<const double> owned_values);
  ~Vector();
  Vector(Vector&& other) noexcept;
  Vector& operator=(Vector&& other) noexcept;
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;

  Vec get() const { return vec_; }
  const Layout& layout() const { return layout_; }
  std::vector<double> owned() const;  // this rank's rows
  // Collective: the whole vector on rank 0 of the layout's communicator, empty elsewhere.
  std::vector<double> gather_to_root() const;

 private:
  Layout layout_;
  Vec vec_ = nullptr;
};

}  // namespace clatter::petsc
