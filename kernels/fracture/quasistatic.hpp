#pragma once
// 003 section 3.1: the quasistatic stress of a free (unconstrained) brittle body under contact
// forces, by the sparse direct least-squares solve of eq. 3 on a linear (constant-strain)
// tetrahedral mesh. The body's stiffness is factorized once (CHOLMOD, supernodal); each contact
// step is then a back substitution. The stresses feed the fracture criterion (pattern.hpp).
#include <Eigen/SparseCore>
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "core/vec3.hpp"
#include "kernels/fracture/tet_mesh.hpp"

namespace clatter::kernels::fracture {

struct NodalForce {
  int node = 0;
  Vec3 force_n{};
};

struct StressField {
  std::vector<Vec3> displacement_m;         // per node; rigid part removed: zero net (mass-weighted) momentum and angular momentum
  std::vector<Mat3> stress_pa;              // per tet, Cauchy stress (small strain, = first Piola-Kirchhoff), symmetric
  std::vector<double> max_principal_pa;     // per tet, largest principal stress (Rankine criterion)
  std::vector<double> energy_density_j_m3;  // per tet, 1/2 sigma:eps
  double strain_energy_j = 0;               // sum over tets of density*volume (= 1/2 u^T K u)
};

class QuasistaticSolver {
 public:
  // Assembles K (isotropic linear elasticity) and the lumped masses (rho V/4 per node per tet),
  // builds V and the rigid-mode data, and factorizes V^T K V once. std::invalid_argument for a
  // mesh with < 4 nodes, a node index out of range, a node in no tetrahedron, an inverted or
  // degenerate tetrahedron (named), a mesh in several pieces, E <= 0, nu outside (-1, 0.5) or
  // rho <= 0.
  QuasistaticSolver(TetMesh mesh, double youngs_pa, double poisson, double rho_kg_m3);
  ~QuasistaticSolver();
  QuasistaticSolver(QuasistaticSolver&&) noexcept;
  QuasistaticSolver& operator=(QuasistaticSolver&&) noexcept;

  const TetMesh& mesh() const;
  std::size_t dofs() const;   // 3N
  double factorize_s() const; // wall time of assembly + factorization (steady_clock)

  // Eq. 3: u* = P V (V^T K V)^{-1} V^T P f, then the per-tet stresses. Forces act on nodes;
  // repeated nodes add. std::invalid_argument for a node out of range. Const and safe to call
  // from several threads at once (the back substitutions themselves take turns: the serial
  // OpenBLAS under CHOLMOD is not reentrant).
  StressField solve(const std::vector<NodalForce>& forces) const;

  // Spreads a contact force acting at point_m (body coordinates, near the surface) over the
  // boundary nodes within radius_m of it, weighted by each node's lumped boundary area (1/3 of
  // its boundary triangles' areas); the nearest boundary node alone when none lies within.
  // Appends to `out`.
  void add_surface_force(std::vector<NodalForce>& out, const Vec3& point_m, const Vec3& force_n,
                         double radius_m) const;

  // The assembled stiffness K (3N x 3N, node-major dofs 3*node + component; both triangles) and
  // the lumped nodal masses, for checks of the solution (K u* = P f).
  const Eigen::SparseMatrix<double>& stiffness() const;
  const std::vector<double>& lumped_mass_kg() const;
  const Vec3& mass_centre_m() const;
  // The six dofs V removes (pinning the rigid motions), ascending.
  const std::array<int, 6>& removed_dofs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Principal stresses of a symmetric 3x3 tensor, descending (closed form).
std::array<double, 3> principal_stresses(const Mat3& sigma_pa);

}  // namespace clatter::kernels::fracture
