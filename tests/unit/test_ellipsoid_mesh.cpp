// The ellipsoid mesher (kernels/fem/ellipsoid_mesh.*): closed, outward, on the surface, quality,
// determinism, and the volume of the curved mesh against 4/3 pi a b c (docs/validation.md).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "kernels/fem/ellipsoid_mesh.hpp"

namespace {
using namespace clatter::kernels::fem;
using Axes = std::array<double, 3>;

double ellipsoid_volume(const Axes& r) { return 4.0 / 3.0 * std::numbers::pi * r[0] * r[1] * r[2]; }

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

TEST(EllipsoidMesh, SphereIsClosedOutwardOnTheSurfaceAndWithinBounds) {
  const Axes r{1, 1, 1};
  const EllipsoidMesh m = mesh_ellipsoid({r, 0.3});
  print_quality("sphere h 0.3", m.quality);
  expect_closed_outward_on_surface(m, r);
  const EllipsoidMeshBounds bounds;
  EXPECT_LE(m.quality.max_radius_edge, bounds.max_radius_edge);
  EXPECT_GE(m.quality.min_dihedral_deg, bounds.min_dihedral_deg);
  EXPECT_GE(m.quality.min_jacobian_ratio, bounds.min_jacobian_ratio);
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

TEST(EllipsoidMesh, SameInputGivesABitIdenticalMesh) {
  const EllipsoidMeshSettings s{{1.0, 0.8, 0.6}, 0.2};
  const EllipsoidMesh a = mesh_ellipsoid(s), b = mesh_ellipsoid(s);
  ASSERT_EQ(a.mesh.nodes_m.cols(), b.mesh.nodes_m.cols());
  EXPECT_TRUE(a.mesh.nodes_m == b.mesh.nodes_m);  // exact, not approximate
  EXPECT_EQ(a.mesh.elements, b.mesh.elements);
  EXPECT_EQ(a.boundary, b.boundary);
}

// Known limit: where h exceeds the surface's curvature radius (the tips of 1:2:4, c^2/a = 0.0625 m;
// the rim of 1:1:0.1, 0.01 m) four-surface-vertex caps remain and fold when curved. The mesher
// must refuse such a mesh, never return it (a curvature-graded surface is the fix; not done).
TEST(EllipsoidMesh, UnderResolvedCurvatureIsRefusedNotReturned) {
  for (const Axes& r : {Axes{0.25, 0.5, 1.0}, Axes{1.0, 1.0, 0.1}}) {
    EXPECT_THROW(mesh_ellipsoid({r, 0.15}), MeshError) << r[0] << ":" << r[1] << ":" << r[2];
  }
}

TEST(EllipsoidMesh, FlatEllipsoidCapsTheEdgeLength) {
  EllipsoidMeshBounds any;
  any.min_jacobian_ratio = -1e300;
  any.max_radius_edge = 1e300;
  any.min_dihedral_deg = 0;
  const EllipsoidMesh m = mesh_ellipsoid({{1.0, 1.0, 0.1}, 0.5}, any);
  EXPECT_NEAR(m.quality.edge_length_m, 2 * 0.1 / 3, 1e-15);  // h capped: 3 edges through 2c
}

TEST(EllipsoidMesh, BadInputsAndFailedQualityAreReported) {
  EXPECT_THROW(mesh_ellipsoid({{1, 0, 1}, 0.2}), std::invalid_argument);
  EXPECT_THROW(mesh_ellipsoid({{1, 1, 1}, -0.2}), std::invalid_argument);
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
