#include "tests/reference/tet_inertia.hpp"

#include <Eigen/Dense>

#include <stdexcept>

namespace clatter::reference {
namespace {

using kernels::fracture::PieceInertia;
using kernels::fracture::TetMesh;
using kernels::fracture::tet_volume_m3;

Eigen::Vector3d eig(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 vec(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

}  // namespace

PieceInertia tet_mesh_inertia(const TetMesh& mesh, double rho_kg_m3) {
  // Second moments of each tetrahedron from its vertices (the exact formula for a uniform
  // tetrahedron: integral of x x^T = V/20 (sum x_i x_i^T + (sum x_i)(sum x_i)^T)).
  double volume = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const double v = tet_volume_m3(mesh, static_cast<int>(t));
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d x = eig(mesh.nodes_m[mesh.tets[t][k]]);
      sum += x;
      outer += x * x.transpose();
    }
    volume += v;
    first += v * sum / 4;
    second += v / 20 * (outer + sum * sum.transpose());
  }
  if (!(volume > 0)) throw std::invalid_argument("tet_mesh_inertia: the mesh has no positive volume");
  const Eigen::Vector3d c = first / volume;
  const Eigen::Matrix3d about_c = rho_kg_m3 * (second - volume * c * c.transpose());  // integral of r r^T about c
  const Eigen::Matrix3d inertia = about_c.trace() * Eigen::Matrix3d::Identity() - about_c;
  PieceInertia p;
  p.mass_kg = rho_kg_m3 * volume;
  p.centre_m = vec(c);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.inertia_kg_m2[i][j] = inertia(i, j);
  return p;
}

}  // namespace clatter::reference
