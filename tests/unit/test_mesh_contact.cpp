// The local radius of curvature of a triangle mesh at a contact (kernels/mesh_contact.hpp) against
// closed forms: a sphere's radius, an ellipsoid's principal curvatures at its axis ends, and a box's
// faces, edges and corners by the rule's radii (docs/synth.md "Contact").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <tuple>

#include "kernels/mesh_contact.hpp"
#include "tests/unit/test_meshes.hpp"

using namespace clatter;
using kernels::ContactFeature;

namespace {

kernels::MeshContactRule rule_of(double rounding_radius_m, double flat_radius_m, double max_offset_m) {
  kernels::MeshContactRule r;
  r.rounding_radius_m = rounding_radius_m;
  r.flat_radius_m = flat_radius_m;
  r.max_offset_m = max_offset_m;
  return r;
}

// A rule whose clamps never bite: the fit alone.
kernels::MeshContactRule unclamped() { return rule_of(1e-9, 1e9, 1); }

kernels::MeshContact contact_of(const io::TriangleMesh& m, const kernels::MeshContactRule& rule) {
  return kernels::MeshContact(m.vertices_m, m.triangles, rule);
}

// Random unit directions, reproducible.
std::vector<Vec3> directions(int n) {
  std::mt19937 gen(7);
  std::normal_distribution<double> g;
  std::vector<Vec3> out;
  while (static_cast<int>(out.size()) < n) {
    const Vec3 d{g(gen), g(gen), g(gen)};
    const double len = std::sqrt(dot(d, d));
    if (len > 1e-3) out.push_back(scale(d, 1 / len));
  }
  return out;
}

}  // namespace

// Points on the true sphere (outside the inscribed mesh by up to its sag) and on the mesh itself
// (a face's centroid, an edge, a vertex): the fit recovers R. The worst error over 200 points is
// what docs/synth.md quotes.
TEST(MeshContact, IcosphereGivesTheSphereRadius) {
  const double radius = 0.1;
  for (const int levels : {3, 4}) {  // 1280 and 5120 triangles
    const auto mesh = test::icosphere(radius, levels, {0.3, -0.2, 0.05});
    const auto contact = contact_of(mesh, unclamped());
    double worst = 0;
    for (const auto& d : directions(200)) {
      const auto c = contact.at({0.3 + radius * d[0], -0.2 + radius * d[1], 0.05 + radius * d[2]});
      EXPECT_EQ(c.feature, ContactFeature::smooth);
      worst = std::max({worst, std::abs(c.radius_m / radius - 1), std::abs(c.curvature_1_per_m * radius - 1),
                        std::abs(c.curvature_2_per_m * radius - 1)});
    }
    const auto& t = mesh.triangles[17];
    const Vec3 centroid = scale(add(add(mesh.vertices_m[t[0]], mesh.vertices_m[t[1]]), mesh.vertices_m[t[2]]), 1.0 / 3);
    for (const Vec3& p : {centroid, scale(add(mesh.vertices_m[t[0]], mesh.vertices_m[t[1]]), 0.5), mesh.vertices_m[t[2]]})
      worst = std::max(worst, std::abs(contact.at(p).radius_m / radius - 1));
    std::printf("icosphere, %zu triangles: worst |R / r - 1| and |kappa r - 1| = %.4f\n", mesh.triangles.size(), worst);
    EXPECT_LT(worst, levels == 3 ? 0.01 : 0.001);
  }
}

// An ellipsoid (a, b, c) = (0.2, 0.12, 0.06) m: at (0, 0, c) the principal curvatures are c / a^2 and
// c / b^2; at (a, 0, 0), a / b^2 and a / c^2 (every point of a stretched icosphere lies on it).
TEST(MeshContact, EllipsoidPrincipalCurvatures) {
  const double a = 0.2, b = 0.12, c = 0.06;
  auto mesh = test::icosphere(1.0, 5);
  for (auto& v : mesh.vertices_m) v = {a * v[0], b * v[1], c * v[2]};
  const auto contact = contact_of(mesh, unclamped());
  const auto pole = contact.at({0, 0, c});
  EXPECT_NEAR(pole.curvature_1_per_m / (c / (b * b)), 1, 0.0003);
  EXPECT_NEAR(pole.curvature_2_per_m / (c / (a * a)), 1, 0.0003);
  EXPECT_NEAR(pole.radius_m / (a * b / c), 1, 0.0003);
  const auto tip = contact.at({a, 0, 0});
  EXPECT_NEAR(tip.curvature_1_per_m / (a / (c * c)), 1, 0.0003);
  EXPECT_NEAR(tip.curvature_2_per_m / (a / (b * b)), 1, 0.0003);
}

// A cylinder r = 5 cm, 20 cm long: on its side kappa_1 = 1 / r across, the axis flat (clamped to
// 1 / R_flat), R = sqrt(r R_flat); its caps are flat, its rims sharp edges. Long side triangles
// (the fit's neighbourhood follows the contact face's shortest edge).
TEST(MeshContact, CylinderSideCapAndRim) {
  const double r = 0.05, r_min = 1e-3, r_flat = 1.0;
  const kernels::MeshContactRule rule = rule_of(r_min, r_flat, 0.05);
  for (const auto& [segments, rings, tolerance] : {std::tuple{64, 8, 0.015}, std::tuple{128, 16, 0.002}}) {
    const auto contact = contact_of(test::cylinder(r, 0.2, segments, rings), rule);
    for (const double angle : {0.0, 0.3, 2.0}) {
      const auto side = contact.at({r * std::cos(angle), r * std::sin(angle), 0.07});
      EXPECT_EQ(side.feature, ContactFeature::smooth);
      EXPECT_NEAR(side.curvature_1_per_m * r, 1, tolerance) << segments << " at " << angle;
      EXPECT_DOUBLE_EQ(side.curvature_2_per_m, 1 / r_flat);
      EXPECT_NEAR(side.radius_m / std::sqrt(r * r_flat), 1, tolerance);
    }
    const auto cap = contact.at({0.01, 0.02, -0.001});
    EXPECT_EQ(cap.feature, ContactFeature::smooth);
    EXPECT_DOUBLE_EQ(cap.radius_m, r_flat);
    const auto rim = contact.at({r * 1.01, 0, 0.2});
    EXPECT_EQ(rim.feature, ContactFeature::edge);
    EXPECT_NEAR(rim.radius_m, std::sqrt(r_min * r_flat), 1e-12);
  }
}

// A 10 cm cube, faces of 1 x 1, 4 x 4 and 8 x 8 squares: a face gives R_flat, an edge sqrt(r_min R_flat), a
// corner r_min, whatever the tessellation; within r_min of an edge counts as on it.
TEST(MeshContact, BoxFaceEdgeAndCornerFollowTheRule) {
  const double side = 0.1, r_min = 1e-3, r_flat = 0.06;
  const kernels::MeshContactRule rule = rule_of(r_min, r_flat, 0.05);
  for (const int n : {1, 4, 8}) {  // 8 x 8: 81 vertices a face, enough for the quartic fit
    const auto contact = contact_of(test::box({side, side, side}, n), rule);
    struct Case {
      Vec3 point;
      ContactFeature feature;
      double radius_m;
    };
    const double edge_r = std::sqrt(r_min * r_flat);
    for (const Case& k : {Case{{0.05, 0.05, 0}, ContactFeature::smooth, r_flat},       // bottom face centre
                          Case{{0.03, 0.07, -0.002}, ContactFeature::smooth, r_flat},  // below the face, off-centre
                          Case{{0.002, 0.05, 0}, ContactFeature::smooth, r_flat},      // 2 r_min from an edge
                          Case{{0.0005, 0.05, 0}, ContactFeature::edge, edge_r},       // r_min / 2 from it
                          Case{{0.05, 0, 0}, ContactFeature::edge, edge_r},            // on the edge
                          Case{{0.05, -0.001, -0.001}, ContactFeature::edge, edge_r},  // outside, nearest the edge
                          Case{{0, 0, 0}, ContactFeature::corner, r_min},
                          Case{{0.1005, 0.1, 0.1}, ContactFeature::corner, r_min},
                          Case{{-0.002, -0.002, -0.002}, ContactFeature::corner, r_min}}) {
      const auto c = contact.at(k.point);
      EXPECT_EQ(c.feature, k.feature) << n << ": " << k.point[0] << " " << k.point[1] << " " << k.point[2];
      EXPECT_NEAR(c.radius_m / k.radius_m, 1, 1e-9) << n << ": " << k.point[0] << " " << k.point[1] << " " << k.point[2];
    }
  }
}

// The rule's radii for a cube of side s, whose proxy is the volume-equal sphere: r_eq = s (3 / 4 pi)^(1/3),
// r_min = 0.02 r_eq, R_flat = r_eq; the offset limit is half the centre-to-corner distance.
TEST(MeshContact, RuleOfACube) {
  const double s = 0.1, m = 2.7;
  const double i = m * s * s / 6;
  const auto proxy = kernels::fit_proxy({{{i, 0, 0}, {0, i, 0}, {0, 0, i}}}, m, s * s * s);
  const auto mesh = test::box({s, s, s});
  const auto rule = kernels::mesh_contact_rule(proxy, s * s * s, mesh.vertices_m, {s / 2, s / 2, s / 2});
  const double r_eq = s * std::cbrt(3 / (4 * std::numbers::pi));
  EXPECT_NEAR(rule.rounding_radius_m, 0.02 * r_eq, 1e-12);
  EXPECT_NEAR(rule.flat_radius_m, r_eq, 1e-12);
  EXPECT_NEAR(rule.max_offset_m, 0.5 * s * std::sqrt(3.0) / 2, 1e-12);
  EXPECT_THROW(kernels::mesh_contact_rule(proxy, 0, mesh.vertices_m, {}), std::invalid_argument);
}

TEST(MeshContact, BadMeshesAndFarPointsThrow) {
  kernels::MeshContactRule rule = rule_of(1e-3, 0.06, 0.02);
  auto cube = test::box({0.1, 0.1, 0.1});
  const auto contact = contact_of(cube, rule);
  EXPECT_THROW(contact.at({0.05, 0.05, -0.03}), std::invalid_argument);  // 3 cm below a face
  EXPECT_THROW(contact.at({0.05, 0.05, std::nan("")}), std::invalid_argument);
  EXPECT_NO_THROW(contact.at({0.05, 0.05, -0.019}));
  auto open = cube;
  open.triangles.pop_back();
  EXPECT_THROW(contact_of(open, rule), std::invalid_argument);
  auto flat = cube;
  for (auto& v : flat.vertices_m) v[2] = 0;  // every triangle collapsed onto the plane z = 0... or a line
  for (auto& v : flat.vertices_m) v[1] = 0;
  EXPECT_THROW(contact_of(flat, rule), std::invalid_argument);
  auto bad_rule = rule;
  bad_rule.flat_radius_m = 1e-4;  // below r_min
  EXPECT_THROW(contact_of(cube, bad_rule), std::invalid_argument);
}
