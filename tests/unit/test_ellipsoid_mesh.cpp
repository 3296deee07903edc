// The ellipsoid mesher (kernels/fem/ellipsoid_mesh.*): closed, outward, on the surface, quality,
// determinism, and the volume of the curved mesh against 4/3 pi a b c (docs/validation.md), for a
// sphere and for cigars and pancakes down to axis ratios of 1:20.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <ostream>
#include <string>

#include "kernels/fem/ellipsoid_mesh.hpp"

namespace {
using namespace clatter::kernels::fem;
using Axes = std::array<double, 3>;

double ellipsoid_volume(const Axes& r) { return 4.0 / 3.0 * std::numbers::pi * r[0] * r[1] * r[2]; }

// Axes in the ratio a : b : c with a^2 + b^2 + c^2 = 1.
Axes unit_axes(const Axes& ratio) {
  const double norm = std::sqrt(ratio[0] * ratio[0] + ratio[1] * ratio[1] + ratio[2] * ratio[2]);
  return {ratio[0] / norm, ratio[1] / norm, ratio[2] / norm};
}

Eigen::Vector3d node(const EllipsoidMesh& m, int i) { return m.mesh.nodes_m.col(i); }

// Sum of element volumes, curved (the mesh's own mid-nodes) or straight (midpoints of the vertices).
double mesh_volume(const EllipsoidMesh& m, bool curved) {
  double v = 0;
  for (const auto& e : m.mesh.elements) {
    Tet10Coords x;
    for (int i = 0; i < kTet10Nodes; ++i) x.col(i) = m.mesh.nodes_m.col(e[i]);
    v += tet10_volume_m3(curved ? x : tet10_straight(x.leftCols<4>()));
  }
  return v;
}

// How far the curved mesh's volume may be from the ellipsoid's. A boundary edge of length L whose
// mid-node moved by s onto the surface: the quadratic through its three nodes takes up the
// surface's second-order term (s ~ L^2 / 8R) exactly, so what is left is the next order, s L / R
// ~ s^2 / L (the O(h^3) boundary error of quadratic geometry); over each face at most its largest
// s^2 / L times its area. The sum bounds the volume error (which cancels further, to O(h^4), on
// smooth parts).
double volume_tolerance_m3(const EllipsoidMesh& m) {
  double tolerance = 0;
  for (const auto& f : m.boundary) {
    const Eigen::Vector3d a = node(m, f[0]), b = node(m, f[1]), c = node(m, f[2]);
    double worst = 0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = node(m, f[k]), q = node(m, f[(k + 1) % 3]);
      const double s = (node(m, f[3 + k]) - 0.5 * (p + q)).norm();
      worst = std::max(worst, s * s / (p - q).norm());
    }
    tolerance += 0.5 * (b - a).cross(c - a).norm() * worst;
  }
  return tolerance;
}

void print_quality(const char* what, const MeshQuality& q) {
  std::printf("%s: h %.4g m, %lld elements, %lld nodes, %lld dofs, radius-edge max %.3f mean %.3f, dihedral %.2f..%.2f "
              "deg, Jacobian ratio min %.3f\n",
              what, q.edge_length_m, q.elements, q.nodes, q.dofs, q.max_radius_edge, q.mean_radius_edge,
              q.min_dihedral_deg, q.max_dihedral_deg, q.min_jacobian_ratio);
}

// Every boundary node on the ellipsoid; every boundary edge in exactly two faces, traversed in
// opposite directions (a closed, consistently oriented surface); each face's normal outward.
void expect_closed_outward_on_surface(const EllipsoidMesh& m, const Axes& r) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : m.boundary) {
    for (int k = 0; k < 6; ++k) {
      const Eigen::Vector3d x = node(m, f[k]);
      const double level = std::pow(x(0) / r[0], 2) + std::pow(x(1) / r[1], 2) + std::pow(x(2) / r[2], 2);
      ASSERT_NEAR(level, 1.0, 1e-12) << "boundary node " << f[k];
    }
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
    const Eigen::Vector3d a = node(m, f[0]), b = node(m, f[1]), c = node(m, f[2]);
    // Outward on an ellipsoid: the face normal agrees with the gradient of the level function.
    const Eigen::Vector3d centroid = (a + b + c) / 3;
    const Eigen::Vector3d gradient(centroid(0) / (r[0] * r[0]), centroid(1) / (r[1] * r[1]), centroid(2) / (r[2] * r[2]));
    EXPECT_GT((b - a).cross(c - a).dot(gradient), 0) << "inward face";
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " twice in one direction";
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << "open edge " << edge.first << "-" << edge.second;
  }
}

void expect_within_bounds(const MeshQuality& q) {
  const EllipsoidMeshBounds bounds;
  EXPECT_LE(q.max_radius_edge, bounds.max_radius_edge);
  EXPECT_GE(q.min_dihedral_deg, bounds.min_dihedral_deg);
  EXPECT_GE(q.min_jacobian_ratio, bounds.min_jacobian_ratio);
}

TEST(EllipsoidMesh, SphereIsClosedOutwardOnTheSurfaceAndWithinBounds) {
  const Axes r{1, 1, 1};
  const EllipsoidMesh m = mesh_ellipsoid({r, 0.3});
  print_quality("sphere h 0.3", m.quality);
  expect_closed_outward_on_surface(m, r);
  expect_within_bounds(m.quality);
  EXPECT_EQ(m.quality.dofs, 3 * m.mesh.nodes_m.cols());
  EXPECT_EQ(m.quality.elements, static_cast<long long>(m.mesh.elements.size()));
}

TEST(EllipsoidMesh, CurvedVolumeConvergesMuchFasterThanStraight) {
  const Axes r{1.0, 0.8, 0.6};
  const double exact = ellipsoid_volume(r);
  const double hs[] = {0.4, 0.2, 0.1};
  double curved[3], straight[3], h_used[3];
  for (int i = 0; i < 3; ++i) {
    const EllipsoidMesh m = mesh_ellipsoid({r, hs[i]});
    h_used[i] = m.quality.edge_length_m;
    curved[i] = std::abs(mesh_volume(m, true) / exact - 1);
    straight[i] = std::abs(mesh_volume(m, false) / exact - 1);
    std::printf("h %.3f: %lld elements, volume error curved %.3e straight %.3e\n", hs[i], m.quality.elements,
                curved[i], straight[i]);
  }
  for (int i = 1; i < 3; ++i) {
    const double order_curved = std::log(curved[i - 1] / curved[i]) / std::log(h_used[i - 1] / h_used[i]);
    const double order_straight = std::log(straight[i - 1] / straight[i]) / std::log(h_used[i - 1] / h_used[i]);
    std::printf("observed order: curved %.2f, straight %.2f\n", order_curved, order_straight);
    EXPECT_GT(order_curved, 3.0);
    EXPECT_NEAR(order_straight, 2.0, 0.3);
    EXPECT_LT(curved[i], 0.01 * straight[i]);
  }
}

// Both a mesh that needs no curvature refinement and a cigar that needs it, and repairs.
TEST(EllipsoidMesh, SameInputGivesABitIdenticalMesh) {
  for (const EllipsoidMeshSettings& s : {EllipsoidMeshSettings{{1.0, 0.8, 0.6}, 0.2},
                                         EllipsoidMeshSettings{unit_axes({1, 3, 10}), 0.1}}) {
    const EllipsoidMesh a = mesh_ellipsoid(s), b = mesh_ellipsoid(s);
    ASSERT_EQ(a.mesh.nodes_m.cols(), b.mesh.nodes_m.cols());
    EXPECT_TRUE(a.mesh.nodes_m == b.mesh.nodes_m);  // exact, not approximate
    EXPECT_EQ(a.mesh.elements, b.mesh.elements);
    EXPECT_EQ(a.boundary, b.boundary);
  }
}

// One shape a : b : c (a^2 + b^2 + c^2 = 1) at one h: within the bounds (no MeshError), closed,
// outward, on the surface, and its curved volume within volume_tolerance_m3. Prints the row of the
// table in docs/validation.md.
struct Shape {
  Axes ratio;
  double h_m;
};

void PrintTo(const Shape& shape, std::ostream* os) {
  *os << shape.ratio[0] << ':' << shape.ratio[1] << ':' << shape.ratio[2] << " h " << shape.h_m << " m";
}

void check_shape(const Shape& shape) {
  const Axes r = unit_axes(shape.ratio);
  const auto t0 = std::chrono::steady_clock::now();
  const EllipsoidMesh m = mesh_ellipsoid({r, shape.h_m});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double error = std::abs(mesh_volume(m, true) - ellipsoid_volume(r)), tolerance = volume_tolerance_m3(m);
  std::printf("| %g:%g:%g | %.2f | %lld | %lld | %.2f | %.2f | %.3f | %.2f | %.1e | %.1e |\n", shape.ratio[0],
              shape.ratio[1], shape.ratio[2], shape.h_m, m.quality.elements, m.quality.dofs, m.quality.max_radius_edge,
              m.quality.min_dihedral_deg, m.quality.min_jacobian_ratio, seconds, error / ellipsoid_volume(r),
              tolerance / ellipsoid_volume(r));
  expect_within_bounds(m.quality);
  expect_closed_outward_on_surface(m, r);
  EXPECT_LE(error, tolerance);
}

std::string shape_name(const testing::TestParamInfo<Shape>& info) {
  char name[64];
  std::snprintf(name, sizeof name, "r%g_%g_%g_h%g", info.param.ratio[0], info.param.ratio[1], info.param.ratio[2],
                info.param.h_m);
  std::string s(name);
  for (char& c : s)
    if (c == '.') c = 'p';
  return s;
}

class EllipsoidShapes : public testing::TestWithParam<Shape> {};
TEST_P(EllipsoidShapes, MeshWithinTheBoundsOnTheSurfaceWithTheVolume) { check_shape(GetParam()); }
INSTANTIATE_TEST_SUITE_P(
    CigarsAndFlatOnes, EllipsoidShapes,
    testing::Values(Shape{{1, 1, 1}, 0.1}, Shape{{1, 1, 1}, 0.25}, Shape{{1, 2, 4}, 0.1}, Shape{{1, 2, 4}, 0.25},
                    Shape{{1, 1, 10}, 0.1}, Shape{{1, 1, 10}, 0.25}, Shape{{1, 1, 20}, 0.1}, Shape{{1, 1, 20}, 0.25},
                    Shape{{1, 3, 10}, 0.1}, Shape{{1, 3, 10}, 0.25}, Shape{{1, 5, 5}, 0.1}, Shape{{1, 5, 5}, 0.25},
                    Shape{{1, 2, 2}, 0.1}, Shape{{1, 2, 2}, 0.25}, Shape{{1, 1, 2}, 0.1}, Shape{{1, 1, 2}, 0.25}),
    shape_name);

// The pancakes: a few seconds each in a release build, so their own suite (tests/CMakeLists.txt
// gives it a longer timeout). 10:10:1 is 1:10:10 with the thin axis along z (the old refusal).
class EllipsoidShapesSlow : public testing::TestWithParam<Shape> {};
TEST_P(EllipsoidShapesSlow, MeshWithinTheBoundsOnTheSurfaceWithTheVolume) { check_shape(GetParam()); }
INSTANTIATE_TEST_SUITE_P(Pancakes, EllipsoidShapesSlow,
                         testing::Values(Shape{{1, 10, 10}, 0.1}, Shape{{1, 10, 10}, 0.25}, Shape{{1, 20, 20}, 0.1},
                                         Shape{{1, 20, 20}, 0.25}, Shape{{10, 10, 1}, 0.15}),
                         shape_name);

// Refinement scales the whole size function, h and k together. A flat 1:3:3 at three levels: the
// volume error falls every time, at an observed order of at least 2.5 over the factor 2, and stays
// within volume_tolerance_m3.
TEST(EllipsoidMesh, FlatEllipsoidVolumeConvergesAtLeastAtOrderTwoAndAHalf) {
  const Axes r = unit_axes({1, 3, 3});
  const double coarsest_h_m = 2 * r[0] / 3, factors[] = {1.5, 2, 3};
  double error[3];
  for (int i = 0; i < 3; ++i) {
    EllipsoidMeshSettings s{r, coarsest_h_m / factors[i]};
    s.spacing_per_curvature_radius = kSpacingPerCurvatureRadius / factors[i];
    const EllipsoidMesh m = mesh_ellipsoid(s);
    error[i] = std::abs(mesh_volume(m, true) - ellipsoid_volume(r));
    std::printf("1:3:3 h %.4f k %.3f: %lld dofs, volume error %.3e (tolerance %.3e)\n", s.edge_length_m,
                s.spacing_per_curvature_radius, m.quality.dofs, error[i] / ellipsoid_volume(r),
                volume_tolerance_m3(m) / ellipsoid_volume(r));
    EXPECT_LE(error[i], volume_tolerance_m3(m));
    if (i > 0) {
      EXPECT_LT(error[i], error[i - 1]);
      std::printf("observed order %.2f\n", std::log(error[i - 1] / error[i]) / std::log(factors[i] / factors[i - 1]));
    }
  }
  const double order = std::log(error[0] / error[2]) / std::log(factors[2] / factors[0]);
  std::printf("observed order over the factor 2: %.2f\n", order);
  EXPECT_GE(order, 2.5);
}

TEST(EllipsoidMesh, CurvatureRadiusAndNearestPoint) {
  EXPECT_NEAR(min_curvature_radius_m({2, 2, 2}, {0, 2, 0}), 2, 1e-14);
  const Axes pancake{0.1, 1, 1};  // the rim's profile: a^2/b; the flat face's: b^2/a
  EXPECT_NEAR(min_curvature_radius_m(pancake, {0, 1, 0}), 0.01, 1e-14);
  EXPECT_NEAR(min_curvature_radius_m(pancake, {0.1, 0, 0}), 10, 1e-12);
  // On a cigar's side the nearest point lies straight out, the ray from the centre off along the axis.
  const Axes cigar{0.05, 0.05, 1};
  const Axes p{0.03, 0, 0.5}, q = nearest_on_ellipsoid(cigar, p), ray = onto_ellipsoid(cigar, p);
  EXPECT_NEAR(q[2], 0.5, 1e-3);
  EXPECT_GT(ray[2] - 0.5, 0.05);
  EXPECT_NEAR(std::pow(q[0] / 0.05, 2) + std::pow(q[2], 2), 1, 1e-14);
  const Axes on{0.03, 0.05 * std::sqrt(0.39), 0.5};  // a point on it stays
  const Axes same = nearest_on_ellipsoid(cigar, on);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(same[i], on[i], 1e-15);
}

TEST(EllipsoidMesh, FlatEllipsoidCapsTheEdgeLength) {
  EllipsoidMeshBounds any;
  any.min_jacobian_ratio = -1e300;
  any.max_radius_edge = 1e300;
  any.min_dihedral_deg = 0;
  const EllipsoidMesh m = mesh_ellipsoid({{1.0, 1.0, 0.1}, 0.5}, any);
  EXPECT_NEAR(m.quality.edge_length_m, 2 * 0.1 / 3, 1e-15);  // h capped: 3 edges through 2c
  // The cap follows elements_through_thickness, and one element through the thickness is a mesh
  // of fewer elements whose volume still converges with the curved faces (within 1 %).
  EllipsoidMeshSettings one{{1.0, 1.0, 0.1}, 0.5};
  one.elements_through_thickness = 1;
  const EllipsoidMesh thin = mesh_ellipsoid(one, any);
  EXPECT_NEAR(thin.quality.edge_length_m, 2 * 0.1, 1e-15);
  EXPECT_LT(thin.quality.elements, m.quality.elements / 3);
  EXPECT_NEAR(mesh_volume(thin, true) / ellipsoid_volume({1.0, 1.0, 0.1}), 1, 1e-2);
  one.elements_through_thickness = 0;
  EXPECT_THROW(mesh_ellipsoid(one, any), std::invalid_argument);
}

TEST(EllipsoidMesh, BadInputsAndFailedQualityAreReported) {
  EXPECT_THROW(mesh_ellipsoid({{1, 0, 1}, 0.2}), std::invalid_argument);
  EXPECT_THROW(mesh_ellipsoid({{1, 1, 1}, -0.2}), std::invalid_argument);
  EllipsoidMeshSettings no_k{{1, 1, 1}, 0.2};
  no_k.spacing_per_curvature_radius = 0;
  EXPECT_THROW(mesh_ellipsoid(no_k), std::invalid_argument);
  EllipsoidMeshBounds impossible;
  impossible.min_dihedral_deg = 80;  // the regular tetrahedron's is 70.5
  try {
    mesh_ellipsoid({{1, 1, 1}, 0.5}, impossible);
    FAIL() << "no MeshError";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("dihedral angle"), std::string::npos) << e.what();
  }
}

}  // namespace

// The layered mesher of flat ellipsoids (mesh_layered_ellipsoid): closed, outward and on the
// surface like TetGen's meshes, conforming (every interior face in exactly two elements, which
// the closed boundary above implies), the same mesh for the same input, and its volume converging
// to 4/3 pi a b c. The rim is where a layered mesh is weakest (the columns collapse there and the
// profile a sqrt(1 - rho^2) has infinite slope), so the error is measured at 1:33 and must fall
// with every halving of h, to below 0.2 %.
TEST(LayeredEllipsoidMesh, ClosedOnTheSurfaceAndVolumeConverges) {
  for (const Axes ratio : {Axes{0.03, 1.0, 1.0}, Axes{0.03, 0.3, 1.0}, Axes{1.0, 0.05, 0.4}}) {
    const Axes r = unit_axes(ratio);
    double previous = HUGE_VAL;
    for (const double h : {0.2, 0.1, 0.05}) {
      LayeredMeshSettings s;
      s.semi_axes_m = r;
      s.edge_length_m = h;
      s.layers = 2;
      const EllipsoidMesh m = mesh_layered_ellipsoid(s);
      expect_closed_outward_on_surface(m, r);
      EXPECT_GT(m.quality.min_jacobian_ratio, 0.2);
      const double error = std::abs(mesh_volume(m, true) / ellipsoid_volume(r) - 1);
      std::printf("layered %.3g:%.3g:%.3g h %.3f: %lld elements, %lld dofs, volume error %.2e, Jacobian ratio %.3f\n",
                  ratio[0], ratio[1], ratio[2], h, m.quality.elements, m.quality.dofs, error, m.quality.min_jacobian_ratio);
      EXPECT_LT(error, previous);
      previous = error;
    }
    EXPECT_LT(previous, 2e-3);
  }
}

TEST(LayeredEllipsoidMesh, SameInputGivesTheSameMeshAndLayersCountThroughTheThickness) {
  LayeredMeshSettings s;
  s.semi_axes_m = unit_axes({0.05, 0.5, 1.0});
  s.edge_length_m = 0.1;
  const EllipsoidMesh a = mesh_layered_ellipsoid(s), b = mesh_layered_ellipsoid(s);
  EXPECT_EQ(a.mesh.elements, b.mesh.elements);
  EXPECT_EQ((a.mesh.nodes_m - b.mesh.nodes_m).cwiseAbs().maxCoeff(), 0.0);
  // One layer against three: the same surface, three times the prisms (fewer at the rim, where
  // collapsed prisms make fewer tetrahedra), and the vertex count of the columns' inner nodes.
  s.layers = 1;
  const EllipsoidMesh one = mesh_layered_ellipsoid(s);
  s.layers = 3;
  const EllipsoidMesh three = mesh_layered_ellipsoid(s);
  EXPECT_EQ(one.boundary.size(), three.boundary.size());
  EXPECT_GT(three.quality.elements, 2.5 * static_cast<double>(one.quality.elements));
  EXPECT_LE(three.quality.elements, 3 * one.quality.elements);
  s.layers = 0;
  EXPECT_THROW(mesh_layered_ellipsoid(s), std::invalid_argument);
}
