// The references for modal models of closed meshes (tests/reference/bar_modes.hpp,
// circular_plate.hpp) against published values and limits, and the meshes of those shapes
// (tests/unit/test_meshes.hpp: bar, disk).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <vector>

#include "io/mesh.hpp"
#include "kernels/mass_properties.hpp"
#include "tests/reference/bar_modes.hpp"
#include "tests/reference/circular_plate.hpp"
#include "tests/unit/test_meshes.hpp"

namespace clatter {
namespace {

using reference::Bar;

constexpr double kPi = std::numbers::pi;

Bar steel_bar(double length_m, double width_m, double depth_m) { return {length_m, width_m, depth_m, 2.0e11, 0.3, 7850}; }

TEST(BarModes, CowperCoefficientAndFreeFreeRoots) {
  EXPECT_NEAR(reference::cowper_shear_coefficient_rectangle(0.3), 13.0 / 15.3, 1e-15);  // 0.8497
  EXPECT_NEAR(reference::cowper_shear_coefficient_rectangle(0.0), 10.0 / 12, 1e-15);
  // cos x cosh x = 1 (e.g. Blevins, Formulas for Natural Frequency and Mode Shape, table 8-1).
  EXPECT_NEAR(reference::free_free_beta_l(1), 4.73004074, 1e-8);
  EXPECT_NEAR(reference::free_free_beta_l(2), 7.85320462, 1e-8);
  EXPECT_NEAR(reference::free_free_beta_l(3), 10.99560784, 1e-8);
}

// The Euler-Bernoulli mode's Rayleigh quotients that set Timoshenko's first-order correction:
// omega_T^2 / omega_EB^2 = 1 - r^2 (Q1 + (E / kG) Q3), r^2 = I / A, Q1 = int phi'^2 / int phi^2,
// Q3 = int phi'''^2 / int phi''^2 (rotary inertia; shear, from the strain energy's minimum over the
// rotation at fixed deflection). Simpson on 20000 intervals of the closed-form mode.
std::pair<double, double> rayleigh_quotients(double length_m) {
  const double bl = reference::free_free_beta_l(1), k = bl / length_m;
  const double sigma = (std::cosh(bl) - std::cos(bl)) / (std::sinh(bl) - std::sin(bl));
  const int n = 20000;
  double i0 = 0, i1 = 0, i2 = 0, i3 = 0;
  for (int j = 0; j <= n; ++j) {
    const double x = k * length_m * j / n, w = (j == 0 || j == n) ? 1 : (j % 2 ? 4 : 2);
    const double ch = std::cosh(x), sh = std::sinh(x), c = std::cos(x), s = std::sin(x);
    const double d0 = ch + c - sigma * (sh + s), d1 = sh - s - sigma * (ch + c), d2 = ch - c - sigma * (sh - s),
                 d3 = sh + s - sigma * (ch - c);
    i0 += w * d0 * d0, i1 += w * d1 * d1, i2 += w * d2 * d2, i3 += w * d3 * d3;
  }
  return {k * k * i1 / i0, k * k * i3 / i2};
}

TEST(BarModes, TimoshenkoTendsToEulerBernoulliAtSecondOrder) {
  const double length_m = 0.5;
  std::vector<double> deficit;
  const auto [q1, q3] = rayleigh_quotients(length_m);
  for (const double depth_over_length : {1.0 / 10, 1.0 / 20, 1.0 / 40, 1.0 / 80, 1.0 / 160}) {
    const Bar bar = steel_bar(length_m, 2 * depth_over_length * length_m, depth_over_length * length_m);
    const double eb = reference::euler_bernoulli_free_free_bending_hz(bar), t = reference::timoshenko_free_free_bending_hz(bar);
    const double r2 = bar.depth_m * bar.depth_m / 12, e_over_kg = 2 * (1 + bar.poisson) / reference::cowper_shear_coefficient_rectangle(bar.poisson);
    const double predicted = r2 * (q1 + e_over_kg * q3), exact = 1 - (t / eb) * (t / eb);
    deficit.push_back(1 - t / eb);
    std::printf("h/L 1/%.0f: Euler-Bernoulli %.6g Hz, Timoshenko %.6g Hz (%.4f %% lower); first order %.4f %%, exact %.4f %% in omega^2\n",
                1 / depth_over_length, eb, t, 100 * (1 - t / eb), 100 * predicted, 100 * exact);
    EXPECT_NEAR(exact / predicted, 1, 2 * predicted) << "first order in (h/L)^2, the rest O((h/L)^4)";
  }
  for (std::size_t i = 1; i < deficit.size(); ++i) std::printf("deficit ratio %.4f\n", deficit[i - 1] / deficit[i]);
  for (std::size_t i = 3; i < deficit.size(); ++i) EXPECT_NEAR(deficit[i - 1] / deficit[i], 4, 0.02) << "(h/L)^2 convergence";
  EXPECT_LT(deficit.back(), 2e-4);
  // Beta L of the slender limit, from the frequency: 4.7300.
  const Bar slender = steel_bar(length_m, 2e-4 * length_m, 1e-4 * length_m);
  const double omega = 2 * kPi * reference::timoshenko_free_free_bending_hz(slender);
  const double area = slender.width_m * slender.depth_m, inertia = slender.width_m * std::pow(slender.depth_m, 3) / 12;
  EXPECT_NEAR(std::sqrt(omega * std::sqrt(slender.rho_kg_m3 * area / (slender.youngs_pa * inertia))) * length_m, 4.7300, 5e-5);
  // The determinant changes sign at the root (a simple root, not a touch).
  const double f = reference::timoshenko_free_free_bending_hz(steel_bar(length_m, 0.02, 0.01));
  EXPECT_LT(reference::timoshenko_free_free_determinant(steel_bar(length_m, 0.02, 0.01), 2 * kPi * f * 0.999) *
                reference::timoshenko_free_free_determinant(steel_bar(length_m, 0.02, 0.01), 2 * kPi * f * 1.001),
            0);
}

// Saint-Venant's J = beta a b^3 against the table in Roark's Formulas for Stress and Strain
// (Young & Budynas, 7th ed., table 10.7 case 4, as in Timoshenko & Goodier, Theory of Elasticity,
// section 109), 3 decimals; and Roark's closed-form fit K = a b^3 [1/3 - 0.21 (b/a)(1 - (b/a)^4 / 12)]
// (sides a >= b; "within 4 %"), and the thin strip's limit a b^3 / 3.
TEST(BarModes, RectangleTorsionConstantMatchesRoark) {
  const std::map<double, double> beta{{1.0, 0.141}, {1.5, 0.196}, {2.0, 0.229}, {2.5, 0.249}, {3.0, 0.263},
                                      {4.0, 0.281}, {5.0, 0.291}, {10.0, 0.312}};
  for (const auto& [ratio, tabulated] : beta) {
    const double j = reference::rectangle_torsion_constant_m4(ratio * 0.01, 0.01) / (ratio * 1e-8);
    const double roark = 1.0 / 3 - 0.21 / ratio * (1 - std::pow(1 / ratio, 4) / 12);
    std::printf("a/b %4.1f: beta %.5f (table %.3f, Roark's fit %.5f)\n", ratio, j, tabulated, roark);
    EXPECT_NEAR(j, tabulated, 6e-4) << "a/b " << ratio;
    EXPECT_NEAR(j / roark, 1, 4e-3) << "a/b " << ratio;
  }
  EXPECT_NEAR(reference::rectangle_torsion_constant_m4(1, 1e-3) / (1e-9 / 3), 1 - 0.630249 * 1e-3, 1e-6);
  EXPECT_EQ(reference::rectangle_torsion_constant_m4(0.02, 0.01), reference::rectangle_torsion_constant_m4(0.01, 0.02));
}

TEST(BarModes, TorsionFrequencyIsSaintVenants) {
  const Bar bar = steel_bar(0.5, 0.02, 0.01);
  const double g = bar.youngs_pa / 2.6, j = reference::rectangle_torsion_constant_m4(0.02, 0.01);
  const double ip = 0.02 * 0.01 * (0.02 * 0.02 + 0.01 * 0.01) / 12;
  EXPECT_NEAR(reference::saint_venant_free_free_torsion_hz(bar) / (std::sqrt(g * j / (bar.rho_kg_m3 * ip)) / 1.0), 1, 1e-14);
  EXPECT_NEAR(reference::saint_venant_free_free_torsion_hz(bar, 2) / reference::saint_venant_free_free_torsion_hz(bar), 2, 1e-14);
  std::printf("steel bar 500 x 20 x 10 mm: bending across 10 mm %.2f Hz (Euler-Bernoulli %.2f), torsion %.2f Hz\n",
              reference::timoshenko_free_free_bending_hz(bar), reference::euler_bernoulli_free_free_bending_hz(bar),
              reference::saint_venant_free_free_torsion_hz(bar));
}

// Kirchhoff's free circular plate, lambda^2 = omega R^2 sqrt(rho t / D):
// - nu = 0.3, the values quoted in the modern literature (lambda = 2.3148, 3.0005, 3.5269, 4.5249,
//   4.6728 for (2,0), (0,1), (3,0), (1,1), (4,0); e.g. Amabili, Pasqualini & Dalpiaz, J. Sound
//   Vib. 1995/1996, free edge), to their 4 decimals;
// - nu = 0.33, Leissa (1969)'s table: 5.253, 9.084, 12.23, 20.52, 21.6, 35.25 for (2,0), (0,1),
//   (3,0), (1,1), (4,0), (2,1). The exact roots differ from it by up to 0.5 % ((4,0): 21.53), the
//   table's older computations; they lie closer to nu = 1/3's (5.251, 9.076, 12.22, 20.52, 21.49,
//   35.24). And the sixth mode is (5,0) at 33.06, which that list skips.
TEST(CircularPlate, FreeEdgeMatchesPublishedValues) {
  const std::vector<reference::PlateMode> at_03 = reference::free_circular_plate_modes(0.3, 5);
  const std::vector<std::array<double, 3>> quoted{{2, 0, 2.3148}, {0, 1, 3.0005}, {3, 0, 3.5269}, {1, 1, 4.5249}, {4, 0, 4.6728}};
  for (std::size_t i = 0; i < quoted.size(); ++i) {
    EXPECT_EQ(at_03[i].diameters_n, quoted[i][0]) << i;
    EXPECT_EQ(at_03[i].circles_s, quoted[i][1]) << i;
    EXPECT_NEAR(std::sqrt(at_03[i].lambda2), quoted[i][2], 6e-5) << i;
  }
  const std::vector<reference::PlateMode> modes = reference::free_circular_plate_modes(0.33, 8);
  for (const auto& m : modes) std::printf("nu 0.33 (n %d, s %d): lambda^2 %.5f\n", m.diameters_n, m.circles_s, m.lambda2);
  struct Expected {
    int n, s;
    double lambda2;
  };
  const std::vector<Expected> leissa{{2, 0, 5.253}, {0, 1, 9.084}, {3, 0, 12.23}, {1, 1, 20.52}, {4, 0, 21.6}, {5, 0, 33.06}, {2, 1, 35.25}};
  for (std::size_t i = 0; i < leissa.size(); ++i) {
    EXPECT_EQ(modes[i].diameters_n, leissa[i].n) << i;
    EXPECT_EQ(modes[i].circles_s, leissa[i].s) << i;
    EXPECT_NEAR(modes[i].lambda2 / leissa[i].lambda2, 1, 5e-3) << i;
  }
}

TEST(CircularPlate, KirchhoffErrorAtThicknessOneFortiethOfTheDiameter) {
  for (const auto& m : reference::free_circular_plate_modes(0.33, 6)) {
    const double ratio = reference::mindlin_over_kirchhoff_estimate(m.lambda2, 2.0 / 40, 0.33);
    std::printf("(n %d, s %d): Mindlin / Kirchhoff ~ %.5f (Kirchhoff %.2f %% high)\n", m.diameters_n, m.circles_s, ratio,
                100 * (1 / ratio - 1));
    EXPECT_LT(1 / ratio - 1, 0.03);
  }
}

// Closed, consistently oriented; the volume and inertia of the solid they bound.
bool closed_and_oriented(const io::TriangleMesh& m) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, count] : edges)
    if (count != 1 || !edges.count({e.second, e.first}) || edges.at({e.second, e.first}) != 1) return false;
  return true;
}

TEST(TestMeshes, BarAndDiskBoundTheirSolids) {
  const io::TriangleMesh bar = test::bar({0.3, 0.02, 0.01}, {60, 4, 2});
  ASSERT_TRUE(closed_and_oriented(bar));
  const auto pb = kernels::mesh_mass_properties(bar.vertices_m, bar.triangles);
  EXPECT_NEAR(pb.volume_m3 / 6e-5, 1, 1e-13);
  EXPECT_NEAR(pb.inertia_per_density_m5[0][0] / (6e-5 * (0.02 * 0.02 + 0.01 * 0.01) / 12), 1, 1e-12);
  EXPECT_NEAR(pb.inertia_per_density_m5[2][2] / (6e-5 * (0.3 * 0.3 + 0.02 * 0.02) / 12), 1, 1e-12);
  for (const int segments : {48, 192}) {
    const double r = 0.1, t = 0.005;  // t / 2R = 1/40
    const io::TriangleMesh d = test::disk(r, t, segments, segments / 6);
    ASSERT_TRUE(closed_and_oriented(d)) << segments;
    const auto pd = kernels::mesh_mass_properties(d.vertices_m, d.triangles);
    const double polygon_m2 = segments / 2.0 * r * r * std::sin(2 * kPi / segments);  // the rim is exact, the rings inside it
    EXPECT_NEAR(pd.volume_m3 / (polygon_m2 * t), 1, 1e-12) << segments;
    EXPECT_NEAR(pd.centroid_m[2], t / 2, 1e-15);
    double longest = 0;
    for (const auto& tri : d.triangles)
      for (int k = 0; k < 3; ++k) {
        const auto &a = d.vertices_m[tri[k]], &b = d.vertices_m[tri[(k + 1) % 3]];
        longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
      }
    EXPECT_LT(longest, 2.5 * 2 * kPi * r / segments) << "no slivers across the face";
    std::printf("disk R %.2f t %.3f, %d segments: %zu triangles, longest edge %.3g mm (rim step %.3g mm)\n", r, t, segments,
                d.triangles.size(), 1e3 * longest, 1e3 * 2 * kPi * r / segments);
  }
}

TEST(TestMeshes, WrittenOBJReadsBackExactly) {
  const io::TriangleMesh d = test::disk(0.1, 0.005, 96, 16);
  const std::string path = (std::filesystem::temp_directory_path() / "clatter-test-disk.obj").string();
  ASSERT_TRUE(test::write_obj(d, path)) << path;
  const io::TriangleMesh back = io::read_obj(path);
  EXPECT_EQ(back.vertices_m, d.vertices_m);
  EXPECT_EQ(back.triangles, d.triangles);
}

}  // namespace
}  // namespace clatter
