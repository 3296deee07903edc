#include "kernels/fem/assembly.hpp"

#include <stdexcept>
#include <string>

namespace clatter::kernels::fem {
namespace {

template <class ElementMatrix>
Eigen::SparseMatrix<double> assemble(const Tet10Mesh& mesh, ElementMatrix element_matrix) {
  const auto n_nodes = mesh.nodes_m.cols();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(mesh.elements.size() * kTet10Dofs * kTet10Dofs);
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    Tet10Coords x;
    for (int i = 0; i < kTet10Nodes; ++i) {
      const int node = mesh.elements[e][i];
      if (node < 0 || node >= n_nodes)
        throw std::out_of_range("assemble: element " + std::to_string(e) + " names node " + std::to_string(node));
      x.col(i) = mesh.nodes_m.col(node);
    }
    const Tet10Matrix m = element_matrix(x);
    for (int i = 0; i < kTet10Dofs; ++i)
      for (int j = 0; j < kTet10Dofs; ++j)
        entries.emplace_back(3 * mesh.elements[e][i / 3] + i % 3, 3 * mesh.elements[e][j / 3] + j % 3, m(i, j));
  }
  Eigen::SparseMatrix<double> global(3 * n_nodes, 3 * n_nodes);
  global.setFromTriplets(entries.begin(), entries.end());  // duplicates are summed
  return global;
}

}  // namespace

Eigen::SparseMatrix<double> assemble_stiffness(const Tet10Mesh& mesh, const model::Material& material,
                                               const TetQuadrature& rule) {
  return assemble(mesh, [&](const Tet10Coords& x) { return tet10_stiffness(x, material, rule); });
}

Eigen::SparseMatrix<double> assemble_mass(const Tet10Mesh& mesh, double rho_kg_m3, const TetQuadrature& rule) {
  return assemble(mesh, [&](const Tet10Coords& x) { return tet10_mass(x, rho_kg_m3, rule); });
}

}  // namespace clatter::kernels::fem
