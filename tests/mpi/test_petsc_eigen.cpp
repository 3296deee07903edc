// Spectrum slicing against closed forms: the linear finite-element Laplacian on a uniform grid of
// [0, 1], K = tridiag(-1, 2, -1)/h and M = h/6 tridiag(1, 4, 1), has lambda_k =
// (6/h^2)(1 - cos(k pi h))/(2 + cos(k pi h)), k = 1..N-1 with Dirichlet ends, k = 0..N free-free.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "core/stage_log.hpp"
#include "petsc/eigen.hpp"
#include "petsc/error.hpp"
#include "petsc/inertia.hpp"

namespace {
using namespace clatter::petsc;

double lambda_exact(int k, int n_elements) {
  const double h = 1.0 / n_elements, c = std::cos(k * std::numbers::pi * h);
  return 6.0 / (h * h) * (1.0 - c) / (2.0 + c);
}
// An interval end halfway between lambda_k and lambda_{k+1}.
double gap_after(int k, int n_elements) { return 0.5 * (lambda_exact(k, n_elements) + lambda_exact(k + 1, n_elements)); }

struct Problem {
  Layout layout;
  Matrix K, M;
};

// `copies` uncoupled copies of the grid (dofs of copy c offset by c * dofs per copy); elements dealt
// round-robin over ranks, so most land on rows another rank owns.
Problem laplacian(MPI_Comm comm, int n_elements, bool dirichlet, int copies = 1) {
  int size = 1, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const double h = 1.0 / n_elements;
  const PetscInt per_copy = dirichlet ? n_elements - 1 : n_elements + 1;
  std::vector<PetscInt> dofs;
  std::vector<double> k_blocks, m_blocks;
  for (int c = 0; c < copies; ++c) {
    for (int e = 0; e < n_elements; ++e) {
      if ((e + c * n_elements) % size != rank) continue;
      for (int node : {e, e + 1}) {
        const PetscInt dof = dirichlet ? node - 1 : node;
        dofs.push_back(dof < 0 || dof >= per_copy ? -1 : dof + c * per_copy);
      }
      k_blocks.insert(k_blocks.end(), {1 / h, -1 / h, -1 / h, 1 / h});
      m_blocks.insert(m_blocks.end(), {h / 3, h / 6, h / 6, h / 3});
    }
  }
  Layout layout(comm, per_copy * copies);
  Pattern pattern(layout, dofs, 2);
  return {layout, assemble_elements(pattern, dofs, k_blocks), assemble_elements(pattern, dofs, m_blocks)};
}

// max |x_i^T M x_j - delta_ij|
double m_orthonormality_error(const Matrix& M, const std::vector<Vector>& x) {
  double worst = 0;
  Vector mx(M.layout());
  for (std::size_t j = 0; j < x.size(); ++j) {
    MatMult(M.get(), x[j].get(), mx.get());
    for (std::size_t i = 0; i < x.size(); ++i) {
      PetscScalar dot = 0;
      VecDot(x[i].get(), mx.get(), &dot);
      worst = std::max(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
    }
  }
  return worst;
}

void expect_pairs_good(const Matrix& M, const EigenSolution& s) {
  for (std::size_t i = 0; i < s.lambdas.size(); ++i) EXPECT_LE(s.relative_residuals[i], 1e-8) << "pair " << i;
  EXPECT_LE(m_orthonormality_error(M, s.vectors), 1e-10);
}

TEST(PetscEigen, DirichletLaplacianEveryEigenvalueInTheInterval) {
  const int n = 200;
  Problem p = laplacian(MPI_COMM_WORLD, n, true);
  const SliceSettings settings{gap_after(4, n), gap_after(30, n)};
  const EigenSolution s = solve_interval(p.K, p.M, settings);
  ASSERT_EQ(s.lambdas.size(), 26u);  // k = 5..30
  EXPECT_EQ(s.below_lo, 4);
  EXPECT_EQ(s.below_hi, 30);
  for (int k = 5; k <= 30; ++k) {
    const double exact = lambda_exact(k, n);
    EXPECT_NEAR(s.lambdas[k - 5], exact, 1e-10 * exact) << "k = " << k;
  }
  expect_pairs_good(p.M, s);
  EXPECT_NE(s.options.find("-st_mat_mumps_icntl_13 1"), std::string::npos);
  EXPECT_GE(s.stats.numeric_factorisations, 1);
}

// One step of inverse iteration against the closed form: the discrete Dirichlet eigenvectors are
// the sines v_k(x_i) = sin(k pi x_i), so (K - sigma M)^-1 M (v_2 + 0.1 v_3) = v_2 / (lambda_2 -
// sigma) + 0.1 v_3 / (lambda_3 - sigma): v_3's part shrinks by (lambda_2 - sigma) / (lambda_3 - sigma).
TEST(PetscEigen, ShiftInvertStepIsTheClosedForm) {
  const int n = 200;
  Problem p = laplacian(MPI_COMM_WORLD, n, true);
  auto sines = [&](double c2, double c3) {
    std::vector<double> owned;
    for (PetscInt row = p.layout.begin(); row < p.layout.end(); ++row) {
      const double x = static_cast<double>(row + 1) / n;
      owned.push_back(c2 * std::sin(2 * std::numbers::pi * x) + c3 * std::sin(3 * std::numbers::pi * x));
    }
    return Vector(p.layout, owned);
  };
  const double l1 = lambda_exact(1, n), l2 = lambda_exact(2, n), l3 = lambda_exact(3, n);
  const double sigma = l2 - 0.01 * (l2 - l1);
  std::vector<Vector> x;
  x.push_back(sines(1, 0.1));
  const auto y = shift_invert(p.K, p.M, sigma, x);
  ASSERT_EQ(y.size(), 1u);
  const Vector expected = sines(1 / (l2 - sigma), 0.1 / (l3 - sigma));
  const auto got = y[0].owned(), want = expected.owned();
  double error = 0, scale = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    error = std::max(error, std::abs(got[i] - want[i]));
    scale = std::max(scale, std::abs(want[i]));
  }
  MPI_Allreduce(MPI_IN_PLACE, &error, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &scale, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_LT(error, 1e-9 * scale);
}

TEST(PetscEigen, DoubleEigenvaluesKeepBothMembers) {
  const int n = 60;
  Problem p = laplacian(MPI_COMM_WORLD, n, true, 2);
  const EigenSolution s = solve_interval(p.K, p.M, {gap_after(2, n), gap_after(17, n)});
  ASSERT_EQ(s.lambdas.size(), 2u * 15);
  for (int k = 3; k <= 17; ++k) {
    const double exact = lambda_exact(k, n);
    EXPECT_NEAR(s.lambdas[2 * (k - 3)], exact, 1e-10 * exact) << "k = " << k;
    EXPECT_NEAR(s.lambdas[2 * (k - 3) + 1], exact, 1e-10 * exact) << "k = " << k;
  }
  expect_pairs_good(p.M, s);
}

TEST(PetscEigen, FreeFreeWithoutDeflationReturnsTheZeroEigenvalue) {
  const int n = 80;
  Problem p = laplacian(MPI_COMM_WORLD, n, false);
  const EigenSolution s = solve_interval(p.K, p.M, {-1.0, gap_after(10, n)});
  ASSERT_EQ(s.lambdas.size(), 11u);
  EXPECT_LE(std::abs(s.lambdas[0]), 1e-8);
}

TEST(PetscEigen, FreeFreeDeflatedLeavesOutTheConstantAndKeepsTheRest) {
  const int n = 80;
  Problem p = laplacian(MPI_COMM_WORLD, n, false);
  std::vector<Vector> null_space;
  null_space.emplace_back(p.layout, std::vector<double>(static_cast<std::size_t>(p.layout.local_size()), 1.0));
  const EigenSolution s = solve_interval(p.K, p.M, {-1.0, gap_after(10, n)}, null_space);
  EXPECT_EQ(s.deflated_in_interval, 1);
  ASSERT_EQ(s.lambdas.size(), 10u);
  for (int k = 1; k <= 10; ++k) {
    const double exact = lambda_exact(k, n);
    EXPECT_NEAR(s.lambdas[k - 1], exact, 1e-10 * exact) << "k = " << k;
  }
  expect_pairs_good(p.M, s);
}

// The pre-solve's path (banks/modal/modal_solve.hpp first_elastic_lambda): one shift below the
// null space, the constant deflated; the lowest eigenvalues are the closed form's k = 1, 2, 3, from
// a shift far below (1000 lambda_1) as from one close to 0.
TEST(PetscEigen, LowestAboveTheDeflatedNullSpace) {
  const int n = 80;
  Problem p = laplacian(MPI_COMM_WORLD, n, false);
  std::vector<Vector> null_space;
  null_space.emplace_back(p.layout, std::vector<double>(static_cast<std::size_t>(p.layout.local_size()), 1.0));
  for (double shift : {-1e-3 * lambda_exact(1, n), -1e3 * lambda_exact(1, n)}) {
    LowestSettings settings;
    settings.shift = shift;
    settings.count = 3;
    settings.tolerance = 1e-12;
    const EigenSolution s = lowest_eigenpairs(p.K, p.M, settings, null_space);
    ASSERT_EQ(s.lambdas.size(), 3u);
    for (int k = 1; k <= 3; ++k)
      EXPECT_NEAR(s.lambdas[static_cast<std::size_t>(k - 1)], lambda_exact(k, n), 1e-10 * lambda_exact(k, n))
          << "k = " << k << ", shift " << shift;
    expect_pairs_good(p.M, s);
  }
  // Without the deflation the constant (lambda = 0) is the lowest.
  LowestSettings plain;
  plain.shift = -1.0;
  EXPECT_LE(std::abs(lowest_eigenpairs(p.K, p.M, plain).lambdas.front()), 1e-8);
}

// The same problem on this task's communicator and on each rank alone (PETSC_COMM_SELF): the
// eigenpairs agree, so a bank does not depend on how many ranks a task had.
TEST(PetscEigen, SameResultsOnAnyNumberOfRanks) {
  const int n = 120;
  Problem world = laplacian(MPI_COMM_WORLD, n, true);
  Problem alone = laplacian(PETSC_COMM_SELF, n, true);
  const SliceSettings settings{gap_after(1, n), gap_after(12, n)};
  const EigenSolution a = solve_interval(world.K, world.M, settings);
  const EigenSolution b = solve_interval(alone.K, alone.M, settings);
  ASSERT_EQ(a.lambdas.size(), b.lambdas.size());
  for (std::size_t i = 0; i < a.lambdas.size(); ++i) {
    EXPECT_NEAR(a.lambdas[i], b.lambdas[i], 1e-12 * b.lambdas[i]) << "pair " << i;
    const std::vector<double> xa = a.vectors[i].gather_to_root(), xb = b.vectors[i].gather_to_root();
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) continue;
    ASSERT_EQ(xa.size(), xb.size());
    double worst = 0;
    for (std::size_t j = 0; j < xa.size(); ++j) worst = std::max(worst, std::abs(xa[j] - xb[j]));
    EXPECT_LE(worst, 1e-12) << "pair " << i;
  }
  EXPECT_EQ(a.options, b.options);
}

TEST(PetscEigen, CountMismatchNamesBothCounts) {
  EXPECT_NO_THROW(check_count(7, 7, 1.0, 2.0));
  try {
    check_count(6, 7, 1.0, 2.0);
    FAIL() << "no CountMismatch";
  } catch (const CountMismatch& e) {
    EXPECT_EQ(e.found(), 6);
    EXPECT_EQ(e.expected(), 7);
    EXPECT_NE(std::string(e.what()).find("found 6 eigenvalues in [1, 2]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("counts 7"), std::string::npos) << e.what();
  }
}

// An end exactly on a (double) eigenvalue: K - lambda_hi M is singular up to rounding, and SLEPc
// may lose count (measured: it reports its own mismatch on one rank and not on two). Either way no
// solve returns a count the inertia contradicts.
TEST(PetscEigen, EndOnAnEigenvalueNeverGivesASilentlyWrongCount) {
  const int n = 60;
  Problem p = laplacian(MPI_COMM_WORLD, n, true, 2);
  try {
    const EigenSolution s = solve_interval(p.K, p.M, {gap_after(2, n), lambda_exact(10, n)});
    EXPECT_EQ(static_cast<PetscInt>(s.lambdas.size()), s.below_hi - s.below_lo);
  } catch (const CountMismatch& e) {
    EXPECT_NE(e.found(), e.expected());
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Mismatch between number of values found and information from inertia"),
              std::string::npos) << e.what();
  }
}

TEST(PetscEigen, RejectsBadSettings) {
  Problem p = laplacian(MPI_COMM_WORLD, 20, true);
  EXPECT_THROW(solve_interval(p.K, p.M, {2.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(solve_interval(p.K, p.M, {1.0, 2.0, 0.0}), std::invalid_argument);
}

// Records the stages --log-view shows and prints a timing line for a larger grid.
TEST(PetscEigen, RecordsItsStages) {
  const int n = 2000;
  Problem p = laplacian(MPI_COMM_WORLD, n, true);
  const EigenSolution s = solve_interval(p.K, p.M, {gap_after(10, n), gap_after(60, n)});
  EXPECT_EQ(s.lambdas.size(), 50u);
  std::vector<std::string> paths;
  for (const auto& e : clatter::stage_log().entries()) paths.push_back(e.path);
  for (const char* want : {"assembly", "eigensolve/setup", "eigensolve/solve", "eigensolve/count check/factor numeric"})
    EXPECT_NE(std::find(paths.begin(), paths.end(), want), paths.end()) << want;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf("[timing] N=%d, 50 pairs: setup %.3f s, solve %.3f s, %d shifts, %lld numeric factorisations "
                "(%.3f s), MUMPS %d MB, rss %.0f MB\n",
                n, s.stats.setup_s, s.stats.solve_s, static_cast<int>(s.stats.shifts), s.stats.numeric_factorisations,
                s.stats.numeric_s, static_cast<int>(s.stats.check_factor.memory_sum_mb), s.stats.memory_max_mb);
}

}  // namespace
