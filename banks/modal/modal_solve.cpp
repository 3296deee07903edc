#include "banks/modal/modal_solve.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <span>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "kernels/modal/mode_basis.hpp"
#include "mpi/interrupt.hpp"
#include "petsc/error.hpp"
#include "petsc/inertia.hpp"
#include "petsc/subspace.hpp"

namespace clatter::jobs {
namespace {

constexpr PetscInt kRigidMotions = 6;
// The pre-solve's shift, -guess x this: below the rigid motions' 0, and close enough to it that
// the shift-inverted first mode stands apart even for a guess 100 times too high (the object
// bank's guess, a sphere's, for a plate); K - shift M stays far from singular for MUMPS.
constexpr double kShiftFraction = 0.01;
// An eigenvalue this far below the guess is a zero-energy mode of a bad mesh, not a vibration.
constexpr double kSpuriousFraction = 1e-8;

petsc::SliceSettings slice(const model::ModalSolveSettings& s, double lo, double hi) {
  petsc::SliceSettings out;
  out.lambda_lo = lo;
  out.lambda_hi = hi;
  out.tolerance = s.tolerance;
  out.max_iterations = static_cast<PetscInt>(s.max_iterations);
  out.nev_per_shift = static_cast<PetscInt>(s.nev_per_shift);
  return out;
}

// Count mismatches and solver failures are the task's, not the sweep's.
petsc::EigenSolution solve_or_fail(const FemModel& m, const petsc::SliceSettings& s) {
  try {
    return petsc::solve_interval(m.K, m.M, s, m.rigid);
  } catch (const petsc::CountMismatch& e) {
    throw TaskFailure(fmt::format("count check: {}", e.what()));
  } catch (const petsc::Error& e) {
    throw TaskFailure(fmt::format("eigen-solve of [{:.6g}, {:.6g}] (rad/s)^2 failed: {}", s.lambda_lo, s.lambda_hi,
                                  e.what()));
  }
}

// The number of kept modes: those up to `keep_to`, then the rest of the cluster at the edge, which
// holds the whole multiplet (kernels/modal/multiplets.hpp checks it afterwards).
std::size_t kept_count(const std::vector<double>& lambdas, double keep_to, double gap) {
  std::size_t n = 0;
  while (n < lambdas.size() && lambdas[n] <= keep_to) ++n;
  while (n > 0 && n < lambdas.size() && std::sqrt(lambdas[n]) <= std::sqrt(lambdas[n - 1]) * (1 + gap)) ++n;
  return n;
}

// Rayleigh-Ritz and the reference-field rule in each cluster; residuals of the final vectors.
void apply_basis_rule(const FemModel& m, const std::vector<petsc::Vector>& reference,
                      const model::ModalSolveSettings& s, ModeSet& set) {
  Stage stage("basis");
  std::vector<double> omegas;
  for (double l : set.lambdas) omegas.push_back(std::sqrt(l));
  const auto clusters = kernels::modal::clusters_by_gap(omegas, s.cluster_gap);
  std::vector<petsc::Vector> vectors;
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const auto [begin, end] = clusters[c];
    const std::span<const petsc::Vector> u(set.vectors.data() + begin, static_cast<std::size_t>(end - begin));
    std::vector<petsc::Vector> ku, mu;
    for (const auto& x : u) {
      ku.push_back(petsc::multiply(m.K, x));
      mu.push_back(petsc::multiply(m.M, x));
    }
    const auto n = static_cast<Eigen::Index>(u.size());
    using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const RowMajor a = Eigen::Map<const RowMajor>(petsc::inner_products(u, ku).data(), n, n);
    const RowMajor b = Eigen::Map<const RowMajor>(petsc::inner_products(u, mu).data(), n, n);
    const RowMajor g = Eigen::Map<const RowMajor>(petsc::inner_products(mu, reference).data(), n,
                                                  static_cast<Eigen::Index>(reference.size()));
    const auto basis = kernels::modal::cluster_basis(a, b, g, s.degenerate_gap);
    set.degenerate_groups += basis.degenerate_groups;
    if (basis.degenerate_groups > 0 && basis.rank_margin < 1e-6)
      spdlog::warn("modal: a degenerate multiplet at {:.6g} rad/s is barely fixed by the reference fields (margin {:.2g})",
                   omegas[static_cast<std::size_t>(begin)], basis.rank_margin);
    const RowMajor t = basis.rotation;
    const std::span<const double> tt(t.data(), static_cast<std::size_t>(t.size()));
    auto rotated = petsc::combine(u, tt, u.size());
    const auto kr = petsc::combine(ku, tt, u.size()), mr = petsc::combine(mu, tt, u.size());
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto at = static_cast<std::size_t>(begin + i);
      set.lambdas[at] = basis.lambdas[static_cast<std::size_t>(i)];
      set.relative_residuals[at] = petsc::relative_residual(kr[static_cast<std::size_t>(i)],
                                                            mr[static_cast<std::size_t>(i)], set.lambdas[at]);
      set.cluster[at] = static_cast<int>(c);
      vectors.push_back(std::move(rotated[static_cast<std::size_t>(i)]));
    }
  }
  set.vectors = std::move(vectors);
}

// A mode over the residual limit after the slicing gets inverse iteration: its whole cluster, one
// step from one factorisation at a shift 1 % of the gap below the cluster (which shrinks every
// other mode's part by the ratio of the distances, and the rigid motions' by far more), then the
// basis rule again; twice at most. The slicing's Krylov spaces resolve worst the lowest mode of a
// wide interval, far from the shifts: sample e004's first mode had 4.4e-8 at k = 9.7
// (docs/modal.md "One entry, step by step", Residuals).
void polish_over_limit(const FemModel& m, const std::vector<petsc::Vector>& reference,
                       const model::ModalSolveSettings& s, ModeSet& set) {
  for (int round = 0; round < 2; ++round) {
    std::set<int> over;
    for (std::size_t i = 0; i < set.lambdas.size(); ++i)
      if (!(set.relative_residuals[i] <= s.residual_limit)) over.insert(set.cluster[i]);
    if (over.empty()) return;
    Stage stage("polish");
    for (int c : over) {
      const auto first = static_cast<std::size_t>(std::find(set.cluster.begin(), set.cluster.end(), c) - set.cluster.begin());
      std::size_t end = first;
      while (end < set.cluster.size() && set.cluster[end] == c) ++end;
      const double below = first > 0 ? set.lambdas[first - 1] : 0.0;
      const double sigma = set.lambdas[first] - 0.01 * (set.lambdas[first] - below);
      spdlog::info("modal: modes {}-{} at {:.6g} Hz over the residual limit (largest {:.3g}): one inverse iteration",
                   first, end - 1, std::sqrt(set.lambdas[first]) / (2 * M_PI),
                   *std::max_element(set.relative_residuals.begin() + static_cast<long>(first),
                                     set.relative_residuals.begin() + static_cast<long>(end)));
      auto improved = petsc::shift_invert(m.K, m.M, sigma, std::span<const petsc::Vector>(set.vectors.data() + first, end - first));
      for (std::size_t k = 0; k < improved.size(); ++k) set.vectors[first + k] = std::move(improved[k]);
    }
    apply_basis_rule(m, reference, s, set);
  }
}

}  // namespace

double first_elastic_lambda(const FemModel& m, double guess, const model::ModalSolveSettings& s) {
  mpi::poll_interrupt(m.layout.comm(), "the first-mode solve");
  petsc::LowestSettings lowest;
  lowest.shift = -kShiftFraction * guess;
  lowest.tolerance = s.tolerance;
  lowest.max_iterations = static_cast<PetscInt>(s.max_iterations);
  petsc::EigenSolution solution;
  try {
    solution = petsc::lowest_eigenpairs(m.K, m.M, lowest, m.rigid);
  } catch (const std::runtime_error& e) {
    throw TaskFailure(fmt::format("the first elastic mode (shift {:.4g} (rad/s)^2) failed: {}", lowest.shift, e.what()));
  }
  const double lambda = solution.lambdas.front();
  if (!(lambda > kSpuriousFraction * guess))
    throw TaskFailure(fmt::format("an eigenvalue {:.4g} (rad/s)^2 near zero besides the 6 rigid motions (guess {:.4g}): "
                                  "a spurious mode (a bad mesh or material)", lambda, guess));
  return lambda;
}

double mesh_frequency_error(const MeshResolution& mesh, double frequency_hz) {
  if (!(mesh.edge_length_m > 0)) return 0;
  return kMeshErrorConstant * std::pow(mesh.edge_length_m * frequency_hz / mesh.shear_speed_m_s, 4);
}

ModeSet solve_modes(const FemModel& m, const std::vector<petsc::Vector>& reference, double lambda1_estimate,
                    const model::ModalSolveSettings& s, const MeshResolution& mesh) {
  const double k = s.f_max_multiple;
  auto hz = [](double lambda) { return std::sqrt(lambda) / (2 * M_PI); };
  const double reach = k * (1 + mesh_frequency_error(mesh, k * hz(lambda1_estimate)));
  double lo = 0.25 * lambda1_estimate, hi = 1.1 * reach * reach * lambda1_estimate;
  for (int attempt = 0;; ++attempt) {
    mpi::poll_interrupt(m.layout.comm(), "the eigen-solve");
    petsc::EigenSolution solution = solve_or_fail(m, slice(s, lo, hi));
    if (solution.below_lo != kRigidMotions)
      throw TaskFailure(fmt::format("{} eigenvalues below {:.6g} (rad/s)^2, a quarter of the first mode's estimate: "
                                    "expected the 6 rigid motions", solution.below_lo, lo));
    if (solution.lambdas.empty()) throw TaskFailure(fmt::format("no mode in [{:.6g}, {:.6g}] (rad/s)^2", lo, hi));
    // FEM frequencies lie above the exact ones by at most the margin up to f_max: a mode whose
    // exact frequency is at most f_max has a discrete one at most f_max (1 + margin).
    model::ModalBand band;
    band.f_max_hz = k * hz(solution.lambdas.front());
    band.mesh_error = mesh_frequency_error(mesh, band.f_max_hz);
    band.keep_to_hz = band.f_max_hz * (1 + band.mesh_error);
    const double keep_to = std::pow(2 * M_PI * band.keep_to_hz, 2);
    const std::size_t kept = kept_count(solution.lambdas, keep_to, s.cluster_gap);
    const double needed = keep_to * (1 + s.cluster_gap) * (1 + s.cluster_gap);
    if (kept == solution.lambdas.size() && needed > hi && attempt < 2) {  // f_1 was overestimated: widen
      spdlog::info("modal: f_1 estimate low by {:.2g} %; solving to {:.6g} (rad/s)^2", 100 * (1 - lambda1_estimate / solution.lambdas.front()), 1.2 * needed);
      hi = 1.2 * needed;
      continue;
    }
    if (kept == solution.lambdas.size() && needed > hi)
      throw TaskFailure("the interval end stays inside the last multiplet after 3 solves");
    ModeSet set;
    set.lambdas.assign(solution.lambdas.begin(), solution.lambdas.begin() + static_cast<long>(kept));
    for (std::size_t i = 0; i < kept; ++i) set.vectors.push_back(std::move(solution.vectors[i]));
    set.relative_residuals.assign(kept, 0);
    set.cluster.assign(kept, 0);
    set.stats = solution.stats;
    set.band = band;
    set.record = {lo, hi, solution.below_lo, solution.below_hi,
                  static_cast<std::int64_t>(solution.lambdas.size()), solution.stats.shifts, 0, solution.options};
    apply_basis_rule(m, reference, s, set);
    polish_over_limit(m, reference, s, set);
    for (std::size_t i = 0; i < kept; ++i)
      if (!(set.relative_residuals[i] <= s.residual_limit))
        throw TaskFailure(fmt::format("mode {} at {:.6g} Hz: relative residual {:.3g} > solver.residual_limit {:.3g}", i,
                                      std::sqrt(set.lambdas[i]) / (2 * M_PI), set.relative_residuals[i],
                                      s.residual_limit));
    return set;
  }
}

}  // namespace clatter::jobs
