#pragma once
// The sign and basis rule of the modal bank: what makes the stored mode shapes a function of the
// mesh alone, not of the eigensolver's start vector, the rank count or the order of its
// iterations (docs/modal.md "Reproducible modes").
//
// Modes are taken in clusters (neighbours closer than the cluster gap, e.g. the 2n + 1 members of
// a sphere's multiplet that the mesh splits slightly). Within a cluster:
//  1. Rayleigh-Ritz: the cluster's vectors U (columns) are replaced by the eigenvectors of the
//     projected pencil (U^T K U, U^T M U). The subspace a cluster spans is well determined (its
//     error is the residual over the gap to the rest of the spectrum), and within it the Ritz
//     vectors are fixed to O(residual^2 / split), so two runs that converged differently agree.
//  2. Members whose Ritz values still agree to `degenerate_gap` (exact multiplets, e.g. on a
//     mirror-symmetric mesh) span a subspace with no preferred basis. Its basis is fixed against
//     reference fields G (vector monomials of the scaled coordinates): with C = U^T M G, a
//     column-pivoted QR C P = Q R is taken and U <- U Q with diag(R) > 0. Any rotation S of U
//     (U S) gives S^T C, whose pivoted QR is S^T Q with the same R, so U Q does not depend on S.
//  3. A single mode is the 1 x 1 case of 2: its sign makes its largest reference projection
//     positive.
// Everything here is dense and small (cluster size x reference fields).
#include <Eigen/Core>
#include <array>
#include <span>
#include <utility>
#include <vector>

namespace clatter::kernels::modal {

// Index ranges [begin, end) of consecutive values (ascending) whose relative gap to the previous
// is below `gap`.
std::vector<std::pair<int, int>> clusters_by_gap(std::span<const double> ascending, double gap);

// The reference fields: component j % 3 times the j / 3-th monomial x^p y^q z^r (p + q + r <= 3,
// graded order) of x / a, y / b, z / c.
inline constexpr int kReferenceFields = 60;
Eigen::Vector3d reference_field(int j, const Eigen::Vector3d& scaled_position);

struct ClusterBasis {
  Eigen::MatrixXd rotation;      // m x m: the new vectors are U * rotation
  std::vector<double> lambdas;   // Ritz values, ascending
  int degenerate_groups = 0;     // groups of 2 or more members fixed by the reference fields
  double rank_margin = 1;        // smallest |R_ii| / |R_00| among the QR-fixed groups (1 if none)
};

// A: U^T K U, B: U^T M U (m x m, symmetric, B positive definite), C: U^T M G (m x kReferenceFields).
ClusterBasis cluster_basis(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                           double degenerate_gap);

}  // namespace clatter::kernels::modal
