#pragma once
// The FEM model of one ellipsoid on a task group: K and M of the 10-node mesh assembled into
// PETSc matrices (kernels/fem element matrices, petsc/ assembly), and the vectors the solve and
// the basis rule need (rigid motions, reference fields).
#include <mpi.h>

#include <vector>

#include "kernels/fem/assembly.hpp"
#include "model/material.hpp"
#include "petsc/matrix.hpp"
#include "petsc/vector.hpp"

namespace clatter::jobs {

struct FemModel {
  petsc::Layout layout;
  petsc::Matrix K, M;
  std::vector<petsc::Vector> rigid;      // 3 translations, 3 rotations about the centre
};

// Collective on `comm`; every rank holds the same `mesh`. Rows are split by whole nodes (3 dofs
// each, node-major); each rank computes the element blocks of a contiguous share of elements.
FemModel assemble_fem(MPI_Comm comm, const kernels::fem::Tet10Mesh& mesh, const model::Material& material);

// The reference fields of kernels/modal/mode_basis.hpp at the layout's rows, positions scaled by
// the semi-axes.
std::vector<petsc::Vector> reference_fields(const petsc::Layout& layout, const kernels::fem::Tet10Mesh& mesh,
                                            const std::array<double, 3>& semi_axes_m);

}  // namespace clatter::jobs
