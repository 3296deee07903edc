#include "banks/modal/modal_fem.hpp"

#include <Eigen/Geometry>

#include "kernels/modal/mode_basis.hpp"
#include "mpi/comm.hpp"
#include "petsc/pattern.hpp"

namespace clatter::jobs {
namespace {

using RowMajor30 = Eigen::Matrix<double, 30, 30, Eigen::RowMajor>;

petsc::Layout node_layout(MPI_Comm comm, PetscInt n_nodes) {
  const int size = mpi::size(comm), rank = mpi::rank(comm);
  const PetscInt local_nodes = n_nodes / size + (rank < n_nodes % size ? 1 : 0);
  return petsc::Layout(comm, 3 * n_nodes, 3 * local_nodes);
}

// One vector per field: field(node position, component) at every owned row.
template <class Field>
petsc::Vector nodal_vector(const petsc::Layout& layout, const kernels::fem::Tet10Mesh& mesh, const Field& field) {
  std::vector<double> v(static_cast<std::size_t>(layout.local_size()));
  for (PetscInt row = layout.begin(); row < layout.end(); ++row)
    v[static_cast<std::size_t>(row - layout.begin())] = field(mesh.nodes_m.col(row / 3), static_cast<int>(row % 3));
  return petsc::Vector(layout, v);
}

}  // namespace

FemModel assemble_fem(MPI_Comm comm, const kernels::fem::Tet10Mesh& mesh, const model::Material& material) {
  const int size = mpi::size(comm), rank = mpi::rank(comm);
  petsc::Layout layout = node_layout(comm, static_cast<PetscInt>(mesh.nodes_m.cols()));
  const auto n_elements = static_cast<long long>(mesh.elements.size());
  const long long e_begin = n_elements * rank / size, e_end = n_elements * (rank + 1) / size;
  std::vector<PetscInt> dofs;
  std::vector<double> k_blocks, m_blocks;
  dofs.reserve(static_cast<std::size_t>(e_end - e_begin) * 30);
  k_blocks.reserve(dofs.capacity() * 30);
  m_blocks.reserve(dofs.capacity() * 30);
  for (long long e = e_begin; e < e_end; ++e) {
    const auto& element = mesh.elements[static_cast<std::size_t>(e)];
    kernels::fem::Tet10Coords x;
    for (int i = 0; i < kernels::fem::kTet10Nodes; ++i) {
      x.col(i) = mesh.nodes_m.col(element[i]);
      for (int c = 0; c < 3; ++c) dofs.push_back(3 * element[i] + c);
    }
    const RowMajor30 k = kernels::fem::tet10_stiffness(x, material);
    const RowMajor30 m = kernels::fem::tet10_mass(x, material.rho_kg_m3);
    k_blocks.insert(k_blocks.end(), k.data(), k.data() + k.size());
    m_blocks.insert(m_blocks.end(), m.data(), m.data() + m.size());
  }
  const petsc::Pattern pattern(layout, dofs, 30);
  FemModel model{layout, petsc::assemble_elements(pattern, dofs, k_blocks),
                 petsc::assemble_elements(pattern, dofs, m_blocks), {}};
  for (int mode = 0; mode < 6; ++mode)
    model.rigid.push_back(nodal_vector(layout, mesh, [mode](const Eigen::Vector3d& p, int c) {
      const Eigen::Vector3d motion = mode < 3 ? Eigen::Vector3d::Unit(mode) : Eigen::Vector3d::Unit(mode - 3).cross(p);
      return motion(c);
    }));
  return model;
}

std::vector<petsc::Vector> reference_fields(const petsc::Layout& layout, const kernels::fem::Tet10Mesh& mesh,
                                            const std::array<double, 3>& r) {
  std::vector<petsc::Vector> fields;
  const Eigen::Vector3d inverse(1 / r[0], 1 / r[1], 1 / r[2]);
  for (int j = 0; j < kernels::modal::kReferenceFields; ++j)
    fields.push_back(nodal_vector(layout, mesh, [&](const Eigen::Vector3d& p, int c) {
      return kernels::modal::reference_field(j, p.cwiseProduct(inverse))(c);
    }));
  return fields;
}

}  // namespace clatter::jobs
