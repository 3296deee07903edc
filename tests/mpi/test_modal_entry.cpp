// One modal-bank entry through the job's own pipeline (banks/modal/modal_job.hpp: pre-solve, mesh rule,
// parallel assembly, spectrum slicing, basis rule), against independent facts (docs/validation.md
// "The modal bank"):
//  - completeness: on a sphere and a 1:2:4 ellipsoid every eigenvalue the inertia counts in the
//    sliced interval is found, the 6 rigid motions lie below it, and the sphere's multiplets have
//    Lamb's multiplicities 2n + 1 (none lost at the interval's end);
//  - scaling (003 eq. 9): a mesh scaled by gamma has frequencies / gamma and shapes gamma^-3/2
//    times the unscaled ones, to solver tolerance, after the basis rule (no sign or basis fix here).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "io/config.hpp"
#include "banks/modal/modal_fem.hpp"
#include "banks/modal/modal_job.hpp"
#include "banks/modal/modal_solve.hpp"
#include "banks/modal/modal_spec.hpp"
#include "petsc/session.hpp"
#include "tests/reference/lamb_sphere.hpp"

namespace {
using namespace clatter;

std::unique_ptr<petsc::Session> g_session;
class PetscEnvironment : public testing::Environment {
 public:
  void SetUp() override { g_session = std::make_unique<petsc::Session>(); }
  void TearDown() override { g_session.reset(); }
};
[[maybe_unused]] testing::Environment* const g_environment = testing::AddGlobalTestEnvironment(new PetscEnvironment);

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

const double kSphere = 1 / std::sqrt(3.0);

std::string samples_text(double a, double b, double c) {
  std::ostringstream out;
  out.precision(17);
  out << "[[" << a << ", " << b << ", " << c << "]]";
  return out.str();
}

jobs::ModalSpec spec_for(const std::string& samples, double f_max_multiple) {
  io::Config config(jobs::modal_schema());
  config.set("patch.samples=" + samples);
  config.set("modes.f_max_multiple=" + std::to_string(f_max_multiple));
  config.set("modes.largest_piece_m=0");  // the band is f_max_multiple x f_1
  return jobs::make_modal_spec(config);
}

std::vector<int> multiplet_sizes(const model::ModalEntry& e) {
  std::vector<int> sizes;
  for (std::size_t i = 0; i < e.modes(); ++i) {
    if (i == 0 || e.cluster[i] != e.cluster[i - 1]) sizes.push_back(0);
    ++sizes.back();
  }
  return sizes;
}

void expect_complete(const model::ModalEntry& e, double f_max_multiple, const char* label) {
  EXPECT_EQ(e.solve.below_lo, 6) << label << ": the rigid motions, and nothing else, below the interval";
  EXPECT_EQ(e.solve.found_in_interval, e.solve.below_hi - e.solve.below_lo) << label << ": found = inertia count";
  ASSERT_GT(e.modes(), 0u);
  // Every mode to k f_1 is kept: the count-checked interval reaches beyond (2 pi k f_1)^2 and
  // every found mode below it is stored (the last stored is the last below k f_1, or the end of
  // the multiplet straddling it).
  const double omega_max = 2 * std::numbers::pi * f_max_multiple * e.frequencies_hz.front();
  EXPECT_GE(e.solve.lambda_hi, omega_max * omega_max) << label;
  EXPECT_LE(e.frequencies_hz.back(), f_max_multiple * e.frequencies_hz.front() * 1.02) << label;
  for (double r : e.relative_residuals) EXPECT_LE(r, 1e-8) << label;
  EXPECT_EQ(e.shapes.size(), e.modes() * e.surface_nodes_m.size() * 3);
}

// Lamb's distinct modes up to f_max_multiple x the first, for the bank's glass (nu = 0.2).
std::vector<int> lamb_multiplicities(double poisson, double f_max_multiple) {
  const auto modes = reference::lamb_sphere_modes(poisson, 12.0);
  std::vector<int> out;
  for (const auto& m : modes)
    if (m.omega_a_over_cs <= f_max_multiple * modes.front().omega_a_over_cs) out.push_back(m.multiplicity);
  return out;
}

TEST(ModalEntry, SphereHasEveryMultipletWithLambsMultiplicity) {
  // 1.9 f_1 lies in a gap of Lamb's spectrum for nu = 0.2 (checked below), so the kept set ends
  // between multiplets, and the mesh split of each (< 0.5 %) stays inside the cluster gap.
  const double k = 1.9;
  const auto spec = spec_for(samples_text(kSphere, kSphere, kSphere), k);
  const auto e = jobs::build_modal_entry(MPI_COMM_WORLD, spec, 0);
  if (rank() != 0) return;
  expect_complete(e, k, "sphere");
  const auto expected = lamb_multiplicities(spec.header.material.poisson, k);
  EXPECT_EQ(multiplet_sizes(e), expected);
}

TEST(ModalEntry, BandGivesTheLargestPieceEveryModeToTheTop) {
  // A glass sphere piece of diameter L (its normalized proxy: radius r = 1/sqrt 3, longest
  // semi-axis c = r) has f_0 = f_1 2c / L by equi-frequency scaling; with modes.largest_piece_m = L
  // it must get every one of Lamb's modes below 20 kHz. L is chosen so that 20 kHz is 1.9 f_0 (in
  // a gap of Lamb's spectrum, so the mesh's 0.2 % on f_1 cannot move a multiplet across).
  io::Config config(jobs::modal_schema());
  config.set("patch.samples=" + samples_text(kSphere, kSphere, kSphere));
  const auto lamb = reference::lamb_sphere_modes(0.2, 12.0);
  const double c_s = 3152.1, r = kSphere;  // glass of the built-in table (checked below)
  const double f1_lamb_hz = lamb.front().omega_a_over_cs * c_s / (2 * std::numbers::pi * r);
  const double top_hz = 20000, piece_m = 1.9 * 2 * r * f1_lamb_hz / top_hz;
  config.set("modes.largest_piece_m=" + std::to_string(piece_m));
  config.set("modes.f_max_multiple=1.2");
  const auto spec = jobs::make_modal_spec(config);
  ASSERT_NEAR(spec.header.material.shear_speed_m_s(), c_s, 0.1);
  const auto e = jobs::build_modal_entry(MPI_COMM_WORLD, spec, 0);
  if (rank() != 0) return;
  EXPECT_NEAR(e.solve.f_max_multiple, 1.9, 0.02) << "k = top L / (2 c f_1) from the pre-solve's f_1";
  expect_complete(e, e.solve.f_max_multiple, "sphere, band from the largest piece");
  EXPECT_EQ(multiplet_sizes(e), lamb_multiplicities(0.2, top_hz / (f1_lamb_hz * 2 * r / piece_m)));
}

TEST(ModalEntry, Ellipsoid124IsComplete) {
  const double s = std::sqrt(21.0);
  const auto spec = spec_for(samples_text(1 / s, 2 / s, 4 / s), 2.5);
  const auto e = jobs::build_modal_entry(MPI_COMM_WORLD, spec, 0);
  if (rank() != 0) return;
  expect_complete(e, 2.5, "1:2:4");
  // D2h has only one-dimensional representations: no multiplets but accidental ones.
  const auto sizes = multiplet_sizes(e);
  EXPECT_EQ(std::count(sizes.begin(), sizes.end(), 1), static_cast<long>(sizes.size()));
}

TEST(ModalEntry, ScaledMeshScalesFrequenciesAndShapes) {
  const auto spec = spec_for(samples_text(kSphere, kSphere, kSphere), 1.5);
  const std::array<double, 3> axes{0.4042260417272216, 0.6467616667635546, 0.6467616667635546};
  const double gamma = 0.37;
  auto mesh = kernels::fem::mesh_ellipsoid({axes, 0.3});
  model::ModalSolveSettings settings;
  settings.f_max_multiple = 1.5;
  std::vector<jobs::ModeSet> sets;
  for (double scale : {1.0, gamma}) {
    auto scaled = mesh.mesh;
    scaled.nodes_m *= scale;
    const std::array<double, 3> scaled_axes{axes[0] * scale, axes[1] * scale, axes[2] * scale};
    const auto model = jobs::assemble_fem(MPI_COMM_WORLD, scaled, spec.header.material);
    const auto reference = jobs::reference_fields(model.layout, scaled, scaled_axes);
    const double lambda1 = jobs::first_elastic_lambda(model, 1e7 / (scale * scale), settings);
    sets.push_back(jobs::solve_modes(model, reference, lambda1, settings));
  }
  ASSERT_EQ(sets[0].lambdas.size(), sets[1].lambdas.size());
  double worst_f = 0, worst_u = 0;
  for (std::size_t i = 0; i < sets[0].lambdas.size(); ++i) {
    worst_f = std::max(worst_f, std::abs(std::sqrt(sets[1].lambdas[i] / sets[0].lambdas[i]) * gamma - 1));
    const auto u0 = sets[0].vectors[i].gather_to_root(), u1 = sets[1].vectors[i].gather_to_root();
    double diff = 0, norm = 0;
    for (std::size_t j = 0; j < u0.size(); ++j) {
      diff += std::pow(u1[j] - std::pow(gamma, -1.5) * u0[j], 2);
      norm += std::pow(std::pow(gamma, -1.5) * u0[j], 2);
    }
    if (!u0.empty()) worst_u = std::max(worst_u, std::sqrt(diff / norm));
  }
  if (rank() == 0) std::printf("%zu modes: frequency x gamma within %.2e, shapes x gamma^1.5 within %.2e\n",
                               sets[0].lambdas.size(), worst_f, worst_u);
  EXPECT_LE(worst_f, 1e-9);
  if (rank() == 0) {
    EXPECT_LE(worst_u, 1e-8);
  }
}

}  // namespace
