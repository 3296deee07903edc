// The Lamb sphere reference (tests/reference/lamb_sphere.*): its root finder against closed forms,
// a published value and a second, independently derived form of the spheroidal equation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "tests/reference/lamb_sphere.hpp"

using namespace clatter::reference;

TEST(LambSphere, TorsionalDegreeOneHasTheClosedForm) {
  // j_2(y) = 0, i.e. tan y = 3 y / (3 - y^2): solved here by bisection on the closed form itself.
  auto g = [](double y) { return (3 - y * y) * std::sin(y) - 3 * y * std::cos(y); };
  double a = 5.5, b = 6.0;
  for (int i = 0; i < 200; ++i) (g(a) < 0) == (g(0.5 * (a + b)) < 0) ? a = 0.5 * (a + b) : b = 0.5 * (a + b);
  const auto roots = lamb_roots([](int n, double y, double) { return lamb_torsional(n, y); }, 1, 0.25, 0.05, 10, 1e-3);
  ASSERT_GE(roots.size(), 2u);
  EXPECT_NEAR(roots[0], 0.5 * (a + b), 1e-13);
  EXPECT_NEAR(roots[0], 5.7635, 1e-4);
  EXPECT_NEAR(roots[1], 9.0950, 1e-4);  // second root of tan y = 3y/(3 - y^2)
  EXPECT_NEAR(std::tan(roots[1]), 3 * roots[1] / (3 - roots[1] * roots[1]), 1e-9);
}

TEST(LambSphere, TorsionalFrequenciesDoNotDependOnPoissonRatio) {
  auto torsional = [](double nu) {
    std::vector<double> y;
    for (const LambMode& m : lamb_sphere_modes(nu, 10))
      if (m.family == LambFamily::torsional) y.push_back(m.omega_a_over_cs);
    return y;
  };
  const auto a = torsional(0.1), b = torsional(0.45);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 7u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]);
}

TEST(LambSphere, PublishedValuesForPoissonRatioOneQuarter) {
  // Lamb (1882) for lambda = mu (nu = 1/4): the gravest spheroidal mode, n = 2 ("football"),
  // at omega a / c_s = 2.640; the gravest torsional mode, n = 2, at 2.501 (any nu).
  const auto modes = lamb_sphere_modes(0.25, 3);
  ASSERT_EQ(modes.size(), 2u);
  EXPECT_EQ(modes[0].family, LambFamily::torsional);
  EXPECT_EQ(modes[0].degree_n, 2);
  EXPECT_NEAR(modes[0].omega_a_over_cs, 2.501, 1e-3);
  EXPECT_EQ(modes[1].family, LambFamily::spheroidal);
  EXPECT_EQ(modes[1].degree_n, 2);
  EXPECT_EQ(modes[1].multiplicity, 5);
  EXPECT_NEAR(modes[1].omega_a_over_cs, 2.640, 1e-3);
}

TEST(LambSphere, RadialModeSolvesItsClosedForm) {
  // n = 0: x cot x = 1 - y^2 / 4 with x = y c_s / c_p.
  for (double nu : {0.0, 0.22, 0.3, 0.45}) {
    // x (not y) sets the spacing of the radial roots: about pi.
    const auto roots = lamb_roots(lamb_spheroidal_determinant, 0, nu, 0.05, 10 * lamb_speed_ratio(nu), 5e-3);
    ASSERT_GE(roots.size(), 3u) << nu;
    for (double y : roots) {
      const double x = y / lamb_speed_ratio(nu);
      EXPECT_NEAR(x * std::cos(x) / std::sin(x), 1 - y * y / 4, 1e-10 * (1 + y * y)) << nu << " " << y;
    }
  }
}

TEST(LambSphere, TwoFormsOfTheSpheroidalEquationHaveTheSameRoots) {
  for (double nu : {0.0, 0.22, 0.3, 0.45})
    for (int n = 1; n <= 8; ++n) {
      const auto a = lamb_roots(lamb_spheroidal_determinant, n, nu, 0.5, 20, 1e-2);
      const auto b = lamb_roots(lamb_spheroidal_saviot, n, nu, 0.5, 20, 1e-2);
      ASSERT_EQ(a.size(), b.size()) << "nu " << nu << " n " << n;
      ASSERT_GT(a.size(), 2u);
      for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-12 * a[k]) << nu << " " << n << " " << k;
    }
}

TEST(LambSphere, FrequencyInHertz) {
  // f = y c_s / (2 pi a): steel-like, a = 5 cm.
  const LambMode m{LambFamily::spheroidal, 2, 0, 5, 2.0};
  const double c_s = std::sqrt(200e9 / (2 * 1.3 * 7800));
  EXPECT_NEAR(lamb_frequency_hz(m, 0.05, 200e9, 0.3, 7800), 2.0 * c_s / (2 * std::numbers::pi * 0.05), 1e-9);
}

TEST(LambSphere, AFinerScanFindsNoOtherRoots) {
  const auto coarse = lamb_sphere_modes(0.3, 8, 2e-2), fine = lamb_sphere_modes(0.3, 8, 1e-3);
  ASSERT_EQ(coarse.size(), fine.size());
  for (std::size_t i = 0; i < fine.size(); ++i) EXPECT_NEAR(coarse[i].omega_a_over_cs, fine[i].omega_a_over_cs, 1e-12);
}

TEST(LambSphere, TheFirstTenModesOfGlassAndSteel) {
  // The tables of docs/validation.md ("Free vibration of an elastic sphere (Lamb)").
  struct Row {
    LambFamily family;
    int n, overtone;
    double y;
  };
  constexpr LambFamily T = LambFamily::torsional, S = LambFamily::spheroidal;
  const std::vector<Row> glass = {{T, 2, 0, 2.501133}, {S, 2, 0, 2.635676}, {S, 1, 0, 3.357925}, {T, 3, 0, 3.864700},
                                  {S, 3, 0, 3.902477}, {S, 0, 0, 4.174699}, {S, 2, 1, 4.776969}, {S, 4, 0, 4.985507},
                                  {T, 4, 0, 5.094616}, {T, 1, 0, 5.763459}};
  const std::vector<Row> steel = {{T, 2, 0, 2.501133}, {S, 2, 0, 2.646217}, {S, 1, 0, 3.529987}, {T, 3, 0, 3.864700},
                                  {S, 3, 0, 3.937401}, {S, 0, 0, 4.995514}, {S, 2, 1, 5.006957}, {S, 4, 0, 5.045915},
                                  {T, 4, 0, 5.094616}, {T, 1, 0, 5.763459}};
  for (const auto& [nu, table] : {std::pair{0.22, glass}, std::pair{0.3, steel}}) {
    const auto modes = lamb_sphere_modes(nu, 5.8);
    ASSERT_EQ(modes.size(), 10u) << nu;
    for (std::size_t i = 0; i < table.size(); ++i) {
      EXPECT_EQ(modes[i].family, table[i].family) << nu << " mode " << i + 1;
      EXPECT_EQ(modes[i].degree_n, table[i].n) << nu << " mode " << i + 1;
      EXPECT_EQ(modes[i].overtone, table[i].overtone) << nu << " mode " << i + 1;
      EXPECT_EQ(modes[i].multiplicity, 2 * table[i].n + 1);
      EXPECT_NEAR(modes[i].omega_a_over_cs, table[i].y, 1e-6) << nu << " mode " << i + 1;
    }
  }
}
