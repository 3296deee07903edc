#include "kernels/fracture/quasistatic.hpp"

#include <cholmod.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

namespace clatter::kernels::fracture {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

// Column a of the rigid modes Phi at a node r_m from the mass centre: three translations, then
// three linearized rotations (e_k x r).
Eigen::Matrix<double, 3, 6> rigid_block(const Vec3& r_m) {
  Eigen::Matrix<double, 3, 6> phi = Eigen::Matrix<double, 3, 6>::Zero();
  for (int k = 0; k < 3; ++k) {
    phi(k, k) = 1;
    Vec3 e{};
    e[k] = 1;
    const Vec3 w = cross(e, r_m);
    for (int i = 0; i < 3; ++i) phi(i, 3 + k) = w[i];
  }
  return phi;
}

// Debian's serial OpenBLAS (libopenblas0-serial, behind CHOLMOD's supernodal BLAS calls) keeps a
// buffer pool without locks: two concurrent BLAS calls corrupt each other's results (seen as
// wrong stresses in Quasistatic.ConcurrentSolvesAgree). Every CHOLMOD call that reaches BLAS
// (factorize, solve) holds this lock, so solvers and solves may run on several threads.
std::mutex& blas_mutex() {
  static std::mutex m;
  return m;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

struct QuasistaticSolver::Impl {
  TetMesh mesh;
  double lambda_pa = 0, mu_pa = 0;
  std::vector<double> volume_m3;
  std::vector<std::array<Vec3, 4>> grad;  // shape-function gradients per tet [1/m]
  std::vector<double> mass_kg;
  Vec3 centre_m{};
  Mat6 gram_inverse;  // (Phi^T M Phi)^{-1}
  Eigen::SparseMatrix<double> k_full;
  std::array<int, 6> removed{};
  std::vector<int> reduced_index;  // dof -> row of V^T K V, -1 for a removed dof
  std::vector<int> boundary_nodes;
  std::vector<double> boundary_area_m2;
  double factorize_s = 0;
  cholmod_common common{};
  cholmod_factor* factor = nullptr;

  Impl() { cholmod_start(&common); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }

  void check_and_measure(double youngs_pa, double poisson, double rho_kg_m3);
  void assemble_stiffness();
  void choose_removed_dofs();
  void factorize();

  // The d'Alembert projection of a force: P f = f - M Phi (Phi^T M Phi)^{-1} Phi^T f. It is the
  // projection orthogonal in the M^{-1} inner product (M^{-1} P is symmetric), not the Euclidean
  // one: it subtracts the inertial load M Phi a of the rigid acceleration a the unbalanced force
  // gives the free body, so P f is self-equilibrated (Phi^T P f = 0: in range(K)) and is the load
  // the body's material actually carries.
  void project_force(Eigen::VectorXd& f) const {
    Vec6 s = Vec6::Zero();
    for (std::size_t i = 0; i < mass_kg.size(); ++i)
      s += rigid_block(sub(mesh.nodes_m[i], centre_m)).transpose() * f.segment<3>(3 * static_cast<Eigen::Index>(i));
    const Vec6 a = gram_inverse * s;
    for (std::size_t i = 0; i < mass_kg.size(); ++i)
      f.segment<3>(3 * static_cast<Eigen::Index>(i)) -= mass_kg[i] * (rigid_block(sub(mesh.nodes_m[i], centre_m)) * a);
  }
  // The matching M-orthogonal removal of the displacement's rigid part (the particular
  // translation and rotation V pinned): afterwards sum m u = 0 and sum m (x - c) x u = 0.
  void remove_rigid_part(Eigen::VectorXd& u) const {
    Vec6 s = Vec6::Zero();
    for (std::size_t i = 0; i < mass_kg.size(); ++i)
      s += mass_kg[i] * (rigid_block(sub(mesh.nodes_m[i], centre_m)).transpose() * u.segment<3>(3 * static_cast<Eigen::Index>(i)));
    const Vec6 a = gram_inverse * s;
    for (std::size_t i = 0; i < mass_kg.size(); ++i)
      u.segment<3>(3 * static_cast<Eigen::Index>(i)) -= rigid_block(sub(mesh.nodes_m[i], centre_m)) * a;
  }
};

void QuasistaticSolver::Impl::check_and_measure(double youngs_pa, double poisson, double rho_kg_m3) {
  if (!(youngs_pa > 0)) throw std::invalid_argument("quasistatic: Young's modulus must be > 0");
  if (!(poisson > -1 && poisson < 0.5)) throw std::invalid_argument("quasistatic: Poisson's ratio must lie in (-1, 0.5)");
  if (!(rho_kg_m3 > 0)) throw std::invalid_argument("quasistatic: density must be > 0");
  const std::size_t n = mesh.nodes_m.size();
  if (n < 4) throw std::invalid_argument("quasistatic: the mesh needs at least 4 nodes");
  if (mesh.tets.empty()) throw std::invalid_argument("quasistatic: the mesh has no tetrahedra");
  lambda_pa = youngs_pa * poisson / ((1 + poisson) * (1 - 2 * poisson));
  mu_pa = youngs_pa / (2 * (1 + poisson));

  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> used(n, 0);
  volume_m3.resize(mesh.tets.size());
  grad.resize(mesh.tets.size());
  mass_kg.assign(n, 0.0);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    for (int v : tet)
      if (v < 0 || static_cast<std::size_t>(v) >= n)
        throw std::invalid_argument("quasistatic: tetrahedron " + std::to_string(t) + " has a node index out of range");
    Eigen::Matrix3d d;  // columns x_a - x_0
    double longest_m = 0;
    for (int a = 1; a < 4; ++a)
      for (int c = 0; c < 3; ++c) d(c, a - 1) = mesh.nodes_m[tet[a]][c] - mesh.nodes_m[tet[0]][c];
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const Vec3 e = sub(mesh.nodes_m[tet[a]], mesh.nodes_m[tet[b]]);
        longest_m = std::max(longest_m, std::sqrt(dot(e, e)));
      }
    const double det = d.determinant();
    if (det <= 0) throw std::invalid_argument("quasistatic: tetrahedron " + std::to_string(t) + " is inverted or flat");
    // A sliver this thin (regular tet: 0.71) makes K ill-conditioned past what double resolves.
    if (det < 1e-10 * longest_m * longest_m * longest_m)
      throw std::invalid_argument("quasistatic: tetrahedron " + std::to_string(t) + " is degenerate");
    volume_m3[t] = det / 6;
    // Rows of D^{-1} are the gradients of the barycentric coordinates 1..3.
    const Eigen::Matrix3d dinv = d.inverse();
    Vec3 g0{};
    for (int a = 1; a < 4; ++a) {
      grad[t][a] = {dinv(a - 1, 0), dinv(a - 1, 1), dinv(a - 1, 2)};
      g0 = sub(g0, grad[t][a]);
    }
    grad[t][0] = g0;
    for (int v : tet) {
      mass_kg[v] += rho_kg_m3 * volume_m3[t] / 4;
      used[v] = 1;
      parent[find_root(parent, v)] = find_root(parent, tet[0]);
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!used[i]) throw std::invalid_argument("quasistatic: node " + std::to_string(i) + " belongs to no tetrahedron");
  for (std::size_t i = 1; i < n; ++i)
    if (find_root(parent, static_cast<int>(i)) != find_root(parent, 0))
      throw std::invalid_argument("quasistatic: the mesh is in several pieces (node " + std::to_string(i) +
                                  " is not connected to node 0); give each piece its own solver");

  double total_kg = 0;
  Vec3 moment{};
  for (std::size_t i = 0; i < n; ++i) {
    total_kg += mass_kg[i];
    moment = add(moment, scale(mesh.nodes_m[i], mass_kg[i]));
  }
  centre_m = scale(moment, 1 / total_kg);
  Mat6 gram = Mat6::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const auto phi = rigid_block(sub(mesh.nodes_m[i], centre_m));
    gram += mass_kg[i] * phi.transpose() * phi;
  }
  gram_inverse = gram.ldlt().solve(Mat6::Identity());

  // Lumped boundary areas for spreading contact forces.
  std::vector<double> area(n, 0.0);
  for (const auto& f : boundary_faces(mesh)) {
    const Vec3& x0 = mesh.nodes_m[f.nodes[0]];
    const Vec3 c = cross(sub(mesh.nodes_m[f.nodes[1]], x0), sub(mesh.nodes_m[f.nodes[2]], x0));
    for (int v : f.nodes) area[v] += std::sqrt(dot(c, c)) / 6;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (area[i] > 0) {
      boundary_nodes.push_back(static_cast<int>(i));
      boundary_area_m2.push_back(area[i]);
    }
}

void QuasistaticSolver::Impl::assemble_stiffness() {
  const std::size_t n = mesh.nodes_m.size();
  // Node adjacency (sorted, self included) gives the 3x3-block sparsity pattern directly: a
  // triplet list would hold 144 entries per tet (GBs for the largest meshes).
  std::vector<std::int64_t> pairs;
  pairs.reserve(mesh.tets.size() * 16);
  for (const auto& tet : mesh.tets)
    for (int a : tet)
      for (int b : tet) pairs.push_back(static_cast<std::int64_t>(a) * static_cast<std::int64_t>(n) + b);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<std::int64_t> node_start(n + 1, 0);  // neighbours of node i: pairs[node_start[i] ..)
  for (auto p : pairs) ++node_start[static_cast<std::size_t>(p / static_cast<std::int64_t>(n)) + 1];
  for (std::size_t i = 0; i < n; ++i) node_start[i + 1] += node_start[i];

  const auto dofs = static_cast<Eigen::Index>(3 * n);
  const auto nnz = static_cast<Eigen::Index>(9 * pairs.size());
  if (nnz > std::numeric_limits<int>::max()) throw std::invalid_argument("quasistatic: mesh too large");
  k_full.resize(dofs, dofs);
  k_full.resizeNonZeros(nnz);
  int* outer = k_full.outerIndexPtr();
  int* inner = k_full.innerIndexPtr();
  double* value = k_full.valuePtr();
  // Column 3j+c holds, for each neighbour i of j in order, rows 3i, 3i+1, 3i+2.
  outer[0] = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const auto deg = static_cast<int>(node_start[j + 1] - node_start[j]);
    for (int c = 0; c < 3; ++c) {
      const std::size_t col = 3 * j + c;
      outer[col + 1] = outer[col] + 3 * deg;
      for (int k = 0; k < deg; ++k) {
        const auto i = static_cast<int>(pairs[static_cast<std::size_t>(node_start[j] + k)] % static_cast<std::int64_t>(n));
        for (int r = 0; r < 3; ++r) inner[outer[col] + 3 * k + r] = 3 * i + r;
      }
    }
  }
  std::fill(value, value + nnz, 0.0);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& tet = mesh.tets[t];
    const auto& g = grad[t];
    const double v = volume_m3[t];
    for (int b = 0; b < 4; ++b) {
      const std::size_t j = static_cast<std::size_t>(tet[b]);
      for (int a = 0; a < 4; ++a) {
        // Block K_ab (rows of node a, columns of node b):
        // V [lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I].
        const std::int64_t key = static_cast<std::int64_t>(j) * static_cast<std::int64_t>(n) + tet[a];
        const auto k = std::lower_bound(pairs.begin() + node_start[j], pairs.begin() + node_start[j + 1], key) -
                       (pairs.begin() + node_start[j]);
        const double gg = dot(g[a], g[b]);
        for (int c = 0; c < 3; ++c) {
          double* col = value + outer[3 * j + c] + 3 * k;
          for (int r = 0; r < 3; ++r)
            col[r] += v * (lambda_pa * g[a][r] * g[b][c] + mu_pa * g[b][r] * g[a][c] + (r == c ? mu_pa * gg : 0.0));
        }
      }
    }
  }
}

void QuasistaticSolver::Impl::choose_removed_dofs() {
  const std::size_t n = mesh.nodes_m.size();
  auto farthest = [&](auto distance) {
    int best = 0;
    double best_d = -1;
    for (std::size_t i = 0; i < n; ++i) {
      const double d = distance(mesh.nodes_m[i]);
      if (d > best_d) best_d = d, best = static_cast<int>(i);
    }
    return best;
  };
  const int a = farthest([&](const Vec3& x) { const Vec3 r = sub(x, centre_m); return dot(r, r); });
  const int b = farthest([&](const Vec3& x) { const Vec3 r = sub(x, mesh.nodes_m[a]); return dot(r, r); });
  const Vec3 ab = sub(mesh.nodes_m[b], mesh.nodes_m[a]);
  const int d = farthest([&](const Vec3& x) { const Vec3 c = cross(ab, sub(x, mesh.nodes_m[a])); return dot(c, c); });
  // The rotations scaled by the pinned span make the 6x6 block's condition number dimensionless.
  const double span_m = std::sqrt(dot(ab, ab));
  double best_cond = std::numeric_limits<double>::infinity();
  for (int skip_b = 0; skip_b < 3; ++skip_b)
    for (int comp_d = 0; comp_d < 3; ++comp_d) {
      std::array<int, 6> dofs{3 * a, 3 * a + 1, 3 * a + 2, 0, 0, 3 * d + comp_d};
      for (int c = 0, k = 3; c < 3; ++c)
        if (c != skip_b) dofs[k++] = 3 * b + c;
      Mat6 block;
      for (int r = 0; r < 6; ++r) {
        const int node = dofs[r] / 3;
        auto phi = rigid_block(sub(mesh.nodes_m[node], centre_m));
        phi.rightCols<3>() /= span_m;
        block.row(r) = phi.row(dofs[r] % 3);
      }
      const Eigen::JacobiSVD<Mat6> svd(block);
      const double cond = svd.singularValues()(0) / svd.singularValues()(5);
      if (cond < best_cond) best_cond = cond, removed = dofs;
    }
  if (!(best_cond < 1e12)) throw std::invalid_argument("quasistatic: the mesh's nodes are (nearly) collinear");
  std::sort(removed.begin(), removed.end());
  reduced_index.assign(3 * n, 0);
  for (int r : removed) reduced_index[static_cast<std::size_t>(r)] = -1;
  int next = 0;
  for (auto& ri : reduced_index)
    if (ri == 0) ri = next++;
}

void QuasistaticSolver::Impl::factorize() {
  // V^T K V: K without the removed rows and columns, its upper triangle for CHOLMOD (stype 1).
  const auto dofs = k_full.cols();
  const auto m = static_cast<std::size_t>(dofs - 6);
  std::vector<int> col_ptr(m + 1, 0), row;
  std::vector<double> val;
  row.reserve(static_cast<std::size_t>(k_full.nonZeros()) / 2 + m);
  val.reserve(row.capacity());
  for (Eigen::Index j = 0; j < dofs; ++j) {
    const int rj = reduced_index[static_cast<std::size_t>(j)];
    if (rj < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(k_full, j); it; ++it) {
      const int ri = reduced_index[static_cast<std::size_t>(it.row())];
      if (ri < 0 || ri > rj) continue;
      row.push_back(ri);
      val.push_back(it.value());
    }
    col_ptr[static_cast<std::size_t>(rj) + 1] = static_cast<int>(row.size());
  }
  common.print = 0;
  common.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse a{};
  a.nrow = a.ncol = m;
  a.nzmax = row.size();
  a.p = col_ptr.data();
  a.i = row.data();
  a.x = val.data();
  a.stype = 1;
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  factor = cholmod_analyze(&a, &common);
  if (!factor) throw std::runtime_error("quasistatic: CHOLMOD analysis failed (status " + std::to_string(common.status) + ")");
  {
    const std::lock_guard<std::mutex> lock(blas_mutex());
    cholmod_factorize(&a, factor, &common);
  }
  if (common.status != CHOLMOD_OK || factor->minor < factor->n)
    throw std::invalid_argument("quasistatic: V^T K V is not positive definite (CHOLMOD status " +
                                std::to_string(common.status) + "); is the mesh one connected solid?");
}

QuasistaticSolver::QuasistaticSolver(TetMesh mesh, double youngs_pa, double poisson, double rho_kg_m3)
    : impl_(std::make_unique<Impl>()) {
  const auto start = std::chrono::steady_clock::now();
  impl_->mesh = std::move(mesh);
  impl_->check_and_measure(youngs_pa, poisson, rho_kg_m3);
  impl_->assemble_stiffness();
  impl_->choose_removed_dofs();
  impl_->factorize();
  impl_->factorize_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

QuasistaticSolver::~QuasistaticSolver() = default;
QuasistaticSolver::QuasistaticSolver(QuasistaticSolver&&) noexcept = default;
QuasistaticSolver& QuasistaticSolver::operator=(QuasistaticSolver&&) noexcept = default;

const TetMesh& QuasistaticSolver::mesh() const { return impl_->mesh; }
std::size_t QuasistaticSolver::dofs() const { return 3 * impl_->mesh.nodes_m.size(); }
double QuasistaticSolver::factorize_s() const { return impl_->factorize_s; }
const Eigen::SparseMatrix<double>& QuasistaticSolver::stiffness() const { return impl_->k_full; }
const std::vector<double>& QuasistaticSolver::lumped_mass_kg() const { return impl_->mass_kg; }
const Vec3& QuasistaticSolver::mass_centre_m() const { return impl_->centre_m; }
const std::array<int, 6>& QuasistaticSolver::removed_dofs() const { return impl_->removed; }

StressField QuasistaticSolver::solve(const std::vector<NodalForce>& forces) const {
  const Impl& im = *impl_;
  const std::size_t n = im.mesh.nodes_m.size();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * n));
  for (const auto& nf : forces) {
    if (nf.node < 0 || static_cast<std::size_t>(nf.node) >= n)
      throw std::invalid_argument("quasistatic: force on node " + std::to_string(nf.node) + ", which the mesh lacks");
    for (int c = 0; c < 3; ++c) f(3 * nf.node + c) += nf.force_n[c];
  }
  im.project_force(f);

  const std::size_t m = 3 * n - 6;
  std::vector<double> rhs(m);
  for (std::size_t i = 0; i < 3 * n; ++i)
    if (im.reduced_index[i] >= 0) rhs[static_cast<std::size_t>(im.reduced_index[i])] = f(static_cast<Eigen::Index>(i));
  // A common of its own per call: cholmod_solve writes its status there, and the factor is only
  // read; the BLAS underneath is serialized (blas_mutex).
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  cholmod_dense b{};
  b.nrow = b.nzmax = b.d = m;
  b.ncol = 1;
  b.x = rhs.data();
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = nullptr;
  {
    const std::lock_guard<std::mutex> lock(blas_mutex());
    x = cholmod_solve(CHOLMOD_A, im.factor, &b, &common);
  }
  if (!x) {
    cholmod_finish(&common);
    throw std::runtime_error("quasistatic: CHOLMOD solve failed");
  }
  const auto* r = static_cast<const double*>(x->x);
  Eigen::VectorXd u(static_cast<Eigen::Index>(3 * n));
  for (std::size_t i = 0; i < 3 * n; ++i)
    u(static_cast<Eigen::Index>(i)) = im.reduced_index[i] >= 0 ? r[im.reduced_index[i]] : 0.0;
  cholmod_free_dense(&x, &common);
  cholmod_finish(&common);
  im.remove_rigid_part(u);

  StressField out;
  out.displacement_m.resize(n);
  for (std::size_t i = 0; i < n; ++i) out.displacement_m[i] = {u(3 * i), u(3 * i + 1), u(3 * i + 2)};
  const std::size_t tets = im.mesh.tets.size();
  out.stress_pa.resize(tets);
  out.max_principal_pa.resize(tets);
  out.energy_density_j_m3.resize(tets);
  for (std::size_t t = 0; t < tets; ++t) {
    Mat3 h{};  // displacement gradient du_i/dx_j
    for (int a = 0; a < 4; ++a) {
      const Vec3& ua = out.displacement_m[static_cast<std::size_t>(im.mesh.tets[t][a])];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) h[i][j] += ua[i] * im.grad[t][a][j];
    }
    Mat3 eps{}, sigma{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) eps[i][j] = 0.5 * (h[i][j] + h[j][i]);
    const double trace = eps[0][0] + eps[1][1] + eps[2][2];
    double energy = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        sigma[i][j] = 2 * im.mu_pa * eps[i][j] + (i == j ? im.lambda_pa * trace : 0.0);
        energy += 0.5 * sigma[i][j] * eps[i][j];
      }
    out.stress_pa[t] = sigma;
    out.max_principal_pa[t] = principal_stresses(sigma)[0];
    out.energy_density_j_m3[t] = energy;
    out.strain_energy_j += energy * im.volume_m3[t];
  }
  return out;
}

void QuasistaticSolver::add_surface_force(std::vector<NodalForce>& out, const Vec3& point_m, const Vec3& force_n,
                                          double radius_m) const {
  const Impl& im = *impl_;
  double total_m2 = 0;
  const std::size_t first = out.size();
  int nearest = -1;
  double nearest_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < im.boundary_nodes.size(); ++k) {
    const Vec3 r = sub(im.mesh.nodes_m[static_cast<std::size_t>(im.boundary_nodes[k])], point_m);
    const double d2 = dot(r, r);
    if (d2 < nearest_d2) nearest_d2 = d2, nearest = im.boundary_nodes[k];
    if (d2 <= radius_m * radius_m) {
      out.push_back({im.boundary_nodes[k], scale(force_n, im.boundary_area_m2[k])});
      total_m2 += im.boundary_area_m2[k];
    }
  }
  if (out.size() == first) {
    if (nearest >= 0) out.push_back({nearest, force_n});
    return;
  }
  for (std::size_t k = first; k < out.size(); ++k) out[k].force_n = scale(out[k].force_n, 1 / total_m2);
}

std::array<double, 3> principal_stresses(const Mat3& s) {
  // Trigonometric solution of the characteristic cubic (Smith 1961) on the deviator, which keeps
  // the hydrostatic part exact and the spread accurate to rounding of the largest entry.
  const double q = (s[0][0] + s[1][1] + s[2][2]) / 3;
  const double off = s[0][1] * s[0][1] + s[0][2] * s[0][2] + s[1][2] * s[1][2];
  const double p2 = (s[0][0] - q) * (s[0][0] - q) + (s[1][1] - q) * (s[1][1] - q) + (s[2][2] - q) * (s[2][2] - q) + 2 * off;
  if (p2 <= 0) return {q, q, q};
  const double p = std::sqrt(p2 / 6);
  Mat3 b;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) b[i][j] = (s[i][j] - (i == j ? q : 0.0)) / p;
  const double det = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0]) +
                     b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]);
  const double phi = std::acos(std::clamp(det / 2, -1.0, 1.0)) / 3;
  const double s1 = q + 2 * p * std::cos(phi);
  const double s3 = q + 2 * p * std::cos(phi + 2 * std::numbers::pi / 3);
  return {s1, 3 * q - s1 - s3, s3};
}

}  // namespace clatter::kernels::fracture
