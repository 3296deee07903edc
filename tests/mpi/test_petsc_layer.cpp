// The PETSc/SLEPc layer on its own (no physics): the session's isolation from the environment,
// errors, layouts and assembly. The eigen-solves are in test_petsc_eigen.cpp.
#include <gtest/gtest.h>
#include <mpi.h>
#include <petscmat.h>

#include <csignal>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/interrupt.hpp"
#include "petsc/error.hpp"
#include "petsc/matrix.hpp"
#include "petsc/options.hpp"
#include "petsc/session.hpp"
#include "petsc/vector.hpp"

namespace {
using namespace clatter::petsc;

// One Session for the binary, after MPI_Init (mpi_test_main.cpp) and gone before MPI_Finalize.
// Clatter's interrupt handlers go in first, as a job would have them, so the test sees whether
// PETSc replaced them.
std::unique_ptr<Session> g_session;
class PetscEnvironment : public testing::Environment {
 public:
  void SetUp() override {
    clatter::install_interrupt_handlers();
    g_session = std::make_unique<Session>();
  }
  void TearDown() override { g_session.reset(); }
};
[[maybe_unused]] testing::Environment* const g_environment = testing::AddGlobalTestEnvironment(new PetscEnvironment);

TEST(PetscSession, NamesTheLibrariesItRunsWith) {
  EXPECT_NE(Session::versions().find("PETSc 3."), std::string::npos) << Session::versions();
  EXPECT_NE(Session::versions().find("SLEPc 3."), std::string::npos) << Session::versions();
}

TEST(PetscSession, IsOncePerProcess) { EXPECT_THROW(Session second, std::logic_error); }

// CTest runs this binary with PETSC_OPTIONS set and a HOME whose .petscrc sets options too
// (tests/CMakeLists.txt); neither may reach PETSc's global database.
TEST(PetscSession, ReadsNoOptionsFromTheEnvironmentOrPetscrc) {
  PetscBool from_env = PETSC_TRUE, from_rc = PETSC_TRUE;
  ASSERT_EQ(PetscOptionsHasName(nullptr, nullptr, "-clatter_from_env", &from_env), 0);
  ASSERT_EQ(PetscOptionsHasName(nullptr, nullptr, "-clatter_from_petscrc", &from_rc), 0);
  EXPECT_FALSE(from_env);
  EXPECT_FALSE(from_rc);
  if (const char* env = std::getenv("PETSC_OPTIONS")) {
    EXPECT_NE(g_session->ignored_environment().find(std::string("PETSC_OPTIONS=") + env), std::string::npos);
  } else {
    GTEST_SKIP() << "PETSC_OPTIONS not set: run through ctest";
  }
}

TEST(PetscSession, LeavesSigtermToClatter) {
  struct sigaction current {};
  sigaction(SIGTERM, nullptr, &current);
  ASSERT_NE(current.sa_handler, SIG_DFL);
  std::raise(SIGTERM);  // PETSc's handler would print a traceback and abort
  EXPECT_TRUE(clatter::interrupt_requested());
  EXPECT_EQ(clatter::interrupt_signal(), SIGTERM);
}

TEST(PetscCheck, ThrowsWithPetscsMessage) {
  EXPECT_NO_THROW(check(0, "nothing"));
  // On PETSC_COMM_SELF each rank fails alone, and nobody waits in a collective.
  Layout layout(PETSC_COMM_SELF, 4);
  const PetscInt element[2] = {0, 1};
  Pattern pattern(layout, element, 2);
  Matrix m(pattern);
  const PetscInt outside[2] = {0, 3};
  const double block[4] = {1, 2, 3, 4};
  m.add_element(element, block);  // fills row 0's preallocation, so (0, 3) needs a malloc
  try {
    m.add_element(outside, block);
    FAIL() << "inserting outside the pattern was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("MatSetValues failed"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("New nonzero"), std::string::npos) << e.what();
    EXPECT_NE(e.code(), 0);
  }
}

TEST(PetscOptions, TextIsOrderedAndScopedEntriesComeAndGo) {
  Options o;
  o.set("-a", "x").set("-flag").set("-b", 0.1).set("-a", "y");
  EXPECT_EQ(o.text(), "-a y\n-flag\n-b 0.10000000000000001\n");
  PetscBool has = PETSC_FALSE;
  {
    ScopedOptions scoped(o, "t1_");
    ASSERT_EQ(PetscOptionsHasName(nullptr, nullptr, "-t1_flag", &has), 0);  // reads it
    EXPECT_TRUE(has);
    EXPECT_EQ(scoped.unused(), (std::vector<std::string>{"-a", "-b"}));
    EXPECT_THROW(ScopedOptions(o, "t1_"), std::logic_error);  // a prefix in use
  }
  ASSERT_EQ(PetscOptionsHasName(nullptr, nullptr, "-t1_flag", &has), 0);
  EXPECT_FALSE(has);
  EXPECT_THROW(o.set("no_dash"), std::invalid_argument);
}

TEST(PetscLayout, SplitsContiguouslyAndNamesOwners) {
  int size = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  Layout layout(MPI_COMM_WORLD, 11);
  ASSERT_EQ(layout.ranges().size(), static_cast<std::size_t>(size + 1));
  EXPECT_EQ(layout.ranges().front(), 0);
  EXPECT_EQ(layout.ranges().back(), 11);
  for (PetscInt row = 0; row < 11; ++row) {
    const int owner = layout.owner(row);
    EXPECT_GE(row, layout.begin(owner));
    EXPECT_LT(row, layout.end(owner));
  }
  EXPECT_THROW(layout.owner(11), std::out_of_range);
  Layout given(MPI_COMM_WORLD, 2 * size, 2);
  EXPECT_EQ(given.begin(), 2 * rank);
}

// A path graph assembled from 2x2 blocks by every rank in turn (most blocks land on rows another
// rank owns), checked against the dense sum.
TEST(PetscMatrix, AssemblesElementBlocksFromAnyRankWithoutReallocating) {
  int size = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const PetscInt n = 9;
  Layout layout(MPI_COMM_WORLD, n);
  std::vector<PetscInt> dofs;
  std::vector<double> blocks;
  for (PetscInt e = 0; e + 1 < n; ++e) {
    if (e % size != rank) continue;
    dofs.insert(dofs.end(), {e, e + 1});
    blocks.insert(blocks.end(), {1.0, -1.0, -1.0, 1.0});
  }
  dofs.insert(dofs.end(), {-1, rank % n});  // a constrained dof: left out
  blocks.insert(blocks.end(), {5.0, 5.0, 5.0, 0.5});
  Pattern pattern(layout, dofs, 2);
  Matrix a = assemble_elements(pattern, dofs, blocks);
  MatInfo info{};
  ASSERT_EQ(MatGetInfo(a.get(), MAT_GLOBAL_SUM, &info), 0);
  EXPECT_EQ(info.mallocs, 0.0);
  EXPECT_EQ(info.nz_used, 3.0 * n - 2);
  for (PetscInt row = layout.begin(); row < layout.end(); ++row) {
    double diagonal = 0;
    ASSERT_EQ(MatGetValues(a.get(), 1, &row, 1, &row, &diagonal), 0);
    const double expected = (row == 0 || row == n - 1 ? 1.0 : 2.0) + (row < size ? 0.5 : 0.0);
    EXPECT_DOUBLE_EQ(diagonal, expected) << "row " << row;
  }
  Vector x(layout, std::vector<double>(static_cast<std::size_t>(layout.local_size()), 1.0));
  const std::vector<double> whole = x.gather_to_root();
  EXPECT_EQ(whole.size(), rank == 0 ? static_cast<std::size_t>(n) : 0u);
}

}  // namespace
