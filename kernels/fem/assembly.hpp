#pragma once
// Global stiffness and mass of a 10-node tetrahedral mesh, for tests and small serial eigen checks
// (the modal bank's parallel assembly will be PETSc's).
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "kernels/fem/tet10.hpp"

namespace clatter::kernels::fem {

struct Tet10Mesh {
  Eigen::Matrix3Xd nodes_m;                                 // one column per node
  std::vector<std::array<int, kTet10Nodes>> elements;       // node indices in the order of tet10.hpp
};

// Node-major global degrees of freedom (3 * node + component), like the element's.
Eigen::SparseMatrix<double> assemble_stiffness(const Tet10Mesh& mesh, const model::Material& material,
                                               const TetQuadrature& rule = keast_degree5());
Eigen::SparseMatrix<double> assemble_mass(const Tet10Mesh& mesh, double rho_kg_m3,
                                          const TetQuadrature& rule = keast_degree5());

}  // namespace clatter::kernels::fem
