// The eigen-solve of lowest_free_mode (the mesh is solid_mesh.cpp's).
//
// A sparse direct factorization of the quadratic problem is too slow here: Eigen's simplicial LDLT
// of a 1280-triangle sphere's 18k degrees of freedom takes seconds (3D fill), and CHOLMOD is not
// a dependency. So the work is split over two spaces:
//   1. The linear space inside the quadratic one (vertex values, mid-nodes interpolated: the
//      prolongation P) is small and sparse enough to factorize: block Lanczos on the shift-inverted
//      coarse pencil gives a start block of good approximate modes.
//   2. LOBPCG (Knyazev 2001) on the quadratic pencil from that block, preconditioned by a two-level
//      V-cycle: damped node-block Jacobi smoothing with the coarse factorization as the coarse
//      solve. Quadratic elements split into linear plus edge-bubble parts with a strengthened
//      Cauchy-Schwarz constant below one, so the preconditioner's quality does not degrade with h.
// K is singular (the six rigid motions) and M SPD, so A = K + s M is SPD for s > 0. s only keeps
// the factorization well conditioned: s = 0.05 (c_s / D)^2, D the bounding-box diagonal, is ~1e-3
// of a sphere's lowest eigenvalue, and a larger ratio (a thin plate) costs iterations, not accuracy.
// The rigid motions (exact null vectors of K: straight elements reproduce them) are M-orthogonally
// removed from every new block, in both spaces.
//
// Block Lanczos, not subspace iteration, on the coarse space: the lowest modes of symmetric debris
// come in near-degenerate clusters (a sphere's T2 quintuplet lies 11 % below its S2 quintuplet),
// where subspace iteration converges at the ratio of neighbouring eigenvalues. Rayleigh-Ritz is on
// (K, M) themselves throughout, so the Ritz values are upper bounds of the discrete eigenvalues.
#include "kernels/fem/lowest_mode.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::kernels::fem {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
// Row-major for the products with blocks of vectors: each row then gathers rows of the block.
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr int kRigidModes = 6;
constexpr double kShiftPerSpeed2 = 0.05;  // s / (c_s / D)^2, see above
constexpr int kCoarseBlocksPerRestart = 12;
constexpr int kCoarseIterations = 6;   // a start block needs no more
constexpr double kDropRatio = 1e-8;    // a new direction this much shorter than before is already spanned
constexpr double kGramDrop = 1e-12;    // LOBPCG: Gram eigenvalues below this (relative) are dependence
constexpr int kPowerIterations = 20;   // for the smoother's damping

// A reproducible pseudo-random value in [-1, 1) (splitmix64): start vectors must not depend on a
// library's distribution algorithm, or results would differ between standard libraries.
double hashed_uniform(std::uint64_t i) {
  std::uint64_t z = i + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-52 - 1;
}

MatrixXd hashed_block(Eigen::Index rows, Eigen::Index cols) {
  MatrixXd v(rows, cols);
  for (Eigen::Index i = 0; i < v.size(); ++i) v.data()[i] = hashed_uniform(static_cast<std::uint64_t>(i));
  return v;
}

// A x for a block of vectors. Eigen's row-major sparse times column-major dense product takes one
// column at a time, a scalar dot product per row; with the block's rows contiguous instead, each
// stored entry updates a whole row of the result, which vectorizes and reads A once.
MatrixXd times(const RowSparse& a, const MatrixXd& x) {
  using RowBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowBlock xr = x;
  RowBlock yr = RowBlock::Zero(a.rows(), x.cols());
  const Eigen::Index b = x.cols();
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* value = a.valuePtr();
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    double* yi = yr.data() + i * b;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const double v = value[k];
      const double* xj = xr.data() + static_cast<Eigen::Index>(inner[k]) * b;
#pragma omp simd
      for (Eigen::Index c = 0; c < b; ++c) yi[c] += v * xj[c];
    }
  }
  return yr;
}

// K u = lambda M u with its rigid motions: translations and infinitesimal rotations about the
// centroid (centred, so that Gram-Schmidt does not cancel large lever arms), M-orthonormal.
struct Pencil {
  RowSparse k, m;
  MatrixXd rigid, m_rigid;  // and M times them
  Pencil(RowSparse k_in, RowSparse m_in, const Eigen::Matrix3Xd& nodes_m);
  void deflate(MatrixXd& w) const { w -= rigid * (m_rigid.transpose() * w); }
  double relative_residual(const VectorXd& y, double lambda) const {
    const VectorXd ky = k * y;
    return (ky - lambda * (m * y)).norm() / ky.norm();
  }
};

Pencil::Pencil(RowSparse k_in, RowSparse m_in, const Eigen::Matrix3Xd& nodes_m)
    : k(std::move(k_in)), m(std::move(m_in)) {
  m.prune(0.0);  // the element mass couples equal components only; the rest are stored zeros
  k.makeCompressed();
  m.makeCompressed();  // times() reads the compressed arrays
  const Eigen::Index n_nodes = nodes_m.cols();
  const Eigen::Vector3d centroid = nodes_m.rowwise().mean();
  rigid.setZero(3 * n_nodes, kRigidModes);
  for (Eigen::Index i = 0; i < n_nodes; ++i) {
    const Eigen::Vector3d r = nodes_m.col(i) - centroid;
    for (int c = 0; c < 3; ++c) {
      rigid(3 * i + c, c) = 1;
      rigid.block<3, 1>(3 * i, 3 + c) = Eigen::Vector3d::Unit(c).cross(r);
    }
  }
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j < kRigidModes; ++j) {
      for (int i = 0; i < j; ++i) rigid.col(j) -= rigid.col(i) * rigid.col(i).dot(m * rigid.col(j));
      rigid.col(j) /= std::sqrt(rigid.col(j).dot(m * rigid.col(j)));
    }
  m_rigid = m * rigid;
}

// The linear space inside the quadratic one: coarse unknowns at the vertices (numbered in order of
// first use), mid-nodes at the mean of their edge's ends (exact on straight edges).
struct Coarse {
  Sparse prolongation;
  Eigen::Matrix3Xd nodes_m;
};

Coarse coarse_space(const Tet10Mesh& mesh) {
  const Eigen::Index n = mesh.nodes_m.cols();
  std::vector<int> coarse(static_cast<std::size_t>(n), -1);
  std::vector<char> done(static_cast<std::size_t>(n), 0);
  std::vector<Eigen::Triplet<double>> entries;
  int n_coarse = 0;
  for (const auto& e : mesh.elements)
    for (int k = 0; k < 4; ++k)
      if (coarse[e[k]] < 0) coarse[e[k]] = n_coarse++;
  Coarse out;
  out.nodes_m.resize(3, n_coarse);
  for (const auto& e : mesh.elements) {
    for (int k = 0; k < kTet10Nodes; ++k) {
      if (done[e[k]]) continue;
      done[e[k]] = 1;
      for (int c = 0; c < 3; ++c) {
        if (k < 4) {
          entries.emplace_back(3 * e[k] + c, 3 * coarse[e[k]] + c, 1.0);
          out.nodes_m.col(coarse[e[k]]) = mesh.nodes_m.col(e[k]);
          continue;
        }
        for (int end : kTet10Edges[k - 4]) entries.emplace_back(3 * e[k] + c, 3 * coarse[e[end]] + c, 0.5);
      }
    }
  }
  out.prolongation.resize(3 * n, 3 * n_coarse);
  out.prolongation.setFromTriplets(entries.begin(), entries.end());
  return out;
}

// M-orthonormalize the columns of w against the rigid motions and `basis`, then among themselves
// (classical Gram-Schmidt, twice); columns that vanish are dropped.
void orthonormalize(const Pencil& p, const MatrixXd& basis, MatrixXd& w) {
  const VectorXd before = w.colwise().norm();
  for (int pass = 0; pass < 2; ++pass) {
    p.deflate(w);
    if (basis.cols() > 0) w -= basis * (basis.transpose() * times(p.m, w));
  }
  Eigen::Index kept = 0;
  for (Eigen::Index j = 0; j < w.cols(); ++j) {
    VectorXd x = w.col(j);
    for (int pass = 0; pass < 2; ++pass) x -= w.leftCols(kept) * (w.leftCols(kept).transpose() * (p.m * x));
    // Euclidean lengths, which the M norm bounds within a mesh-size factor: a column that shrank
    // by kDropRatio is rounding, not a new direction.
    if (!(x.norm() > kDropRatio * before(j))) continue;
    w.col(kept++) = x / std::sqrt(x.dot(p.m * x));
  }
  w.conservativeResize(Eigen::NoChange, kept);
}

// The lowest `block` Ritz vectors of the pencil by block Lanczos on (K + s M)^{-1} M, restarted
// from the lowest Ritz vectors when the basis is full; a few steps only: it is LOBPCG's start.
MatrixXd lanczos_start(const Pencil& p, const Eigen::SimplicialLDLT<Sparse>& shifted, int block) {
  const Eigen::Index free_dofs = p.k.rows() - kRigidModes;
  const Eigen::Index capacity = std::min<Eigen::Index>(kCoarseBlocksPerRestart * block, free_dofs);
  MatrixXd q(p.k.rows(), 0), v = hashed_block(p.k.rows(), block), ritz_vectors;
  orthonormalize(p, q, v);
  for (int step = 0;; ++step) {
    q.conservativeResize(Eigen::NoChange, q.cols() + v.cols());
    q.rightCols(v.cols()) = v;
    const MatrixXd kq = times(p.k, q), mq = times(p.m, q);
    const MatrixXd gk = 0.5 * (q.transpose() * kq + kq.transpose() * q);
    const MatrixXd gm = 0.5 * (q.transpose() * mq + mq.transpose() * q);
    const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> ritz(gk, gm);
    if (ritz.info() != Eigen::Success) throw std::runtime_error("lowest_free_mode: coarse Rayleigh-Ritz failed");
    ritz_vectors = q * ritz.eigenvectors().leftCols(std::min<Eigen::Index>(block, q.cols()));
    if (step + 1 >= kCoarseIterations) return ritz_vectors;
    MatrixXd w;
    if (q.cols() + block > capacity) {
      w = ritz_vectors;
      q.resize(Eigen::NoChange, 0);
    } else {
      w = shifted.solve(times(p.m, v));
    }
    orthonormalize(p, q, w);
    if (w.cols() == 0) return ritz_vectors;  // an invariant subspace: the Ritz pairs are exact
    v = std::move(w);
  }
}

// The preconditioner T ~ A^{-1}: a symmetric V(1,1) cycle, omega D^{-1} smoothing (D the 3x3 node
// blocks of A) around the Galerkin coarse solve P (P^T A P)^{-1} P^T. Symmetric positive definite
// while omega lambda_max(D^{-1} A) < 2; omega = 1 / (a power-iteration estimate of lambda_max).
class TwoLevel {
 public:
  TwoLevel(const RowSparse& a, const Sparse& prolongation, const Eigen::SimplicialLDLT<Sparse>& coarse);
  MatrixXd apply(const MatrixXd& r) const {
    MatrixXd x = smooth(r);
    x += p_ * coarse_.solve(MatrixXd(p_.transpose() * (r - times(a_, x))));
    x += smooth(r - times(a_, x));
    return x;
  }

 private:
  MatrixXd smooth(const MatrixXd& r) const {
    MatrixXd y(r.rows(), r.cols());
    for (std::size_t i = 0; i < d_inv_.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(3 * i);
      y.middleRows<3>(row).noalias() = omega_ * d_inv_[i] * r.middleRows<3>(row);
    }
    return y;
  }
  const RowSparse& a_;
  const Sparse& p_;
  const Eigen::SimplicialLDLT<Sparse>& coarse_;
  std::vector<Eigen::Matrix3d> d_inv_;
  double omega_ = 1;
};

TwoLevel::TwoLevel(const RowSparse& a, const Sparse& prolongation, const Eigen::SimplicialLDLT<Sparse>& coarse)
    : a_(a), p_(prolongation), coarse_(coarse),
      d_inv_(static_cast<std::size_t>(a.rows() / 3), Eigen::Matrix3d::Zero()) {
  std::vector<Eigen::Matrix3d> d(d_inv_.size(), Eigen::Matrix3d::Zero());
  for (Eigen::Index row = 0; row < a.outerSize(); ++row)
    for (RowSparse::InnerIterator it(a, row); it; ++it)
      if (it.col() / 3 == row / 3) d[static_cast<std::size_t>(row / 3)](row % 3, it.col() % 3) = it.value();
  for (std::size_t i = 0; i < d.size(); ++i) d_inv_[i] = d[i].inverse();
  VectorXd v = hashed_block(a.rows(), 1);
  double lambda_max = 1;
  for (int it = 0; it < kPowerIterations; ++it) {
    v /= v.norm();
    omega_ = 1;
    v = smooth(times(a, v));
    lambda_max = v.norm();
  }
  omega_ = 1 / lambda_max;
}

// Rayleigh-Ritz on span(S) for (K, M) given K S and M S: S is first M-orthonormalized through
// the eigen-decomposition of its scaled Gram matrix (SVQB, Stathopoulos & Wu 2002), dropping
// directions LOBPCG's nearly dependent blocks leave; returns the coefficients of the lowest
// `want` Ritz vectors and their values.
struct Ritz {
  MatrixXd coefficients;
  VectorXd lambda;
};

Ritz rayleigh_ritz(const MatrixXd& s, const MatrixXd& ks, const MatrixXd& ms, Eigen::Index want) {
  const MatrixXd gm = 0.5 * (s.transpose() * ms + ms.transpose() * s);
  const MatrixXd gk = 0.5 * (s.transpose() * ks + ks.transpose() * s);
  const VectorXd scale = gm.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> gram(scale.asDiagonal() * gm * scale.asDiagonal());
  const VectorXd& theta = gram.eigenvalues();
  Eigen::Index first = 0;
  while (theta(first) < kGramDrop * theta(theta.size() - 1)) ++first;
  const Eigen::Index kept = theta.size() - first;
  const MatrixXd c0 = scale.asDiagonal() * gram.eigenvectors().rightCols(kept) *
                      theta.tail(kept).cwiseSqrt().cwiseInverse().asDiagonal();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> reduced(c0.transpose() * gk * c0);
  const Eigen::Index n = std::min(want, kept);
  return {c0 * reduced.eigenvectors().leftCols(n), reduced.eigenvalues().head(n)};
}

double to_hz(double lambda) { return std::sqrt(std::max(lambda, 0.0)) / (2 * std::numbers::pi); }

// LOBPCG from the block x: converged when the two lowest Ritz values move by less than
// `tolerance` (relative) in a step and their residuals are below sqrt(tolerance) (a Ritz value's
// error is quadratic in its eigenvector's).
void lobpcg(const Pencil& p, const TwoLevel& t, MatrixXd x, const LowestModeSettings& settings, LowestMode& out) {
  p.deflate(x);
  const MatrixXd kx0 = times(p.k, x), mx0 = times(p.m, x);
  Ritz ritz = rayleigh_ritz(x, kx0, mx0, x.cols());
  x = x * ritz.coefficients;
  MatrixXd kx = kx0 * ritz.coefficients, mx = mx0 * ritz.coefficients;
  MatrixXd dir(x.rows(), 0), kdir = dir, mdir = dir;  // LOBPCG's P: the last step's update
  VectorXd previous = VectorXd::Constant(ritz.lambda.size(), std::numeric_limits<double>::infinity());
  const Eigen::Index watched = std::min<Eigen::Index>(2, ritz.lambda.size());
  for (out.iterations = 1;; ++out.iterations) {
    const MatrixXd r = kx - mx * ritz.lambda.asDiagonal();
    bool converged = true;
    for (Eigen::Index j = 0; j < watched; ++j) {
      const double residual = r.col(j).norm() / kx.col(j).norm();
      if (j == 0) out.relative_residual = residual;
      converged = converged && std::abs(previous(j) - ritz.lambda(j)) <= settings.tolerance * ritz.lambda(j) &&
                  residual <= std::sqrt(settings.tolerance);
    }
    out.frequency_hz = to_hz(ritz.lambda(0));
    out.second_frequency_hz = watched > 1 ? to_hz(ritz.lambda(1)) : 0;
    if (converged) break;
    if (out.iterations >= settings.max_iterations)
      throw std::runtime_error("lowest_free_mode: no convergence in " + std::to_string(settings.max_iterations) +
                               " iterations (relative residual " + std::to_string(out.relative_residual) + ")");
    previous = ritz.lambda;
    MatrixXd w = t.apply(r);
    p.deflate(w);
    const Eigen::Index nx = x.cols(), nw = w.cols(), nd = dir.cols(), ns = nx + nw + nd;
    MatrixXd s(x.rows(), ns), ks(x.rows(), ns), ms(x.rows(), ns);
    s << x, w, dir;
    ks << kx, times(p.k, w), kdir;
    ms << mx, times(p.m, w), mdir;
    ritz = rayleigh_ritz(s, ks, ms, nx);
    const MatrixXd update = ritz.coefficients.bottomRows(nw + nd);
    dir = s.rightCols(nw + nd) * update;
    kdir = ks.rightCols(nw + nd) * update;
    mdir = ms.rightCols(nw + nd) * update;
    x = s * ritz.coefficients;
    kx = ks * ritz.coefficients;
    mx = ms * ritz.coefficients;
  }
  out.relative_residual = p.relative_residual(x.col(0), ritz.lambda(0));  // afresh: no drift
}

}  // namespace

LowestMode lowest_free_mode(const std::vector<std::array<double, 3>>& vertices_m,
                            const std::vector<std::array<int, 3>>& triangles, double youngs_pa, double poisson,
                            double rho_kg_m3, const LowestModeSettings& settings) {
  model::Material material;
  material.youngs_pa = youngs_pa, material.poisson = poisson, material.rho_kg_m3 = rho_kg_m3;
  if (const std::string bad = model::check_material(material); !bad.empty())
    throw std::invalid_argument("lowest_free_mode: " + bad);
  if (!(settings.tolerance > 0) || settings.max_iterations < 1 || settings.block_size < 2)
    throw std::invalid_argument("lowest_free_mode: need tolerance > 0, max_iterations >= 1, block_size >= 2");
  double h_m = settings.edge_length_m;
  if (h_m == 0) h_m = std::cbrt(std::max(enclosed_volume_m3(vertices_m, triangles), 0.0)) / 2;
  if (!(h_m > 0)) h_m = 1;  // a surface enclosing no volume: the mesher refuses it with the reason
  return lowest_free_mode_of(tetrahedralize_surface(vertices_m, triangles, h_m), material, settings, true);
}

LowestMode lowest_free_mode_of(const Tet10Mesh& mesh, const model::Material& material, const LowestModeSettings& settings,
                               bool straight) {
  if (const std::string bad = model::check_material(material); !bad.empty())
    throw std::invalid_argument("lowest_free_mode: " + bad);
  if (!(settings.tolerance > 0) || settings.max_iterations < 1 || settings.block_size < 2)
    throw std::invalid_argument("lowest_free_mode: need tolerance > 0, max_iterations >= 1, block_size >= 2");
  LowestMode out;
  out.elements = static_cast<std::int64_t>(mesh.elements.size());
  out.nodes = mesh.nodes_m.cols();
  out.dofs = 3 * out.nodes;
  for (const auto& e : mesh.elements) {
    Tet10Coords x;
    for (int k = 0; k < kTet10Nodes; ++k) x.col(k) = mesh.nodes_m.col(e[k]);
    out.volume_m3 += straight ? tet10_volume_m3(x, keast_degree2()) : tet10_volume_m3(x);
  }
  // Straight elements: the stiffness integrand is quadratic, the mass's quartic; curved ones are
  // rational, integrated by the degree-5 rule.
  const Pencil fine(assemble_stiffness(mesh, material, straight ? keast_degree2() : keast_degree5()),
                    assemble_mass(mesh, material.rho_kg_m3), mesh.nodes_m);
  const Coarse coarse = coarse_space(mesh);
  const Sparse& pr = coarse.prolongation;
  const Pencil linear(RowSparse(pr.transpose() * fine.k * pr), RowSparse(pr.transpose() * fine.m * pr), coarse.nodes_m);
  const double c_s_m_s = material.shear_speed_m_s();
  const double d_m = (mesh.nodes_m.rowwise().maxCoeff() - mesh.nodes_m.rowwise().minCoeff()).norm();
  const double shift_s2 = kShiftPerSpeed2 * (c_s_m_s / d_m) * (c_s_m_s / d_m);
  const Eigen::SimplicialLDLT<Sparse> coarse_shifted(Sparse(linear.k + shift_s2 * linear.m));
  if (coarse_shifted.info() != Eigen::Success) throw std::runtime_error("lowest_free_mode: K + s M did not factorize");
  RowSparse shifted = fine.k + shift_s2 * fine.m;
  shifted.makeCompressed();
  const TwoLevel preconditioner(shifted, pr, coarse_shifted);
  const int block = static_cast<int>(std::min<Eigen::Index>(settings.block_size, linear.k.rows() - kRigidModes));
  lobpcg(fine, preconditioner, pr * lanczos_start(linear, coarse_shifted, block), settings, out);
  return out;
}

}  // namespace clatter::kernels::fem
