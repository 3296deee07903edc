// The object mesher (kernels/fem/object_mesh.*): element counts, quality, orientation, volume and
// boundary area against the exact solid, curved where the input is smooth and flat where it is
// not, determinism, sizing through the thickness of a disk and a bar, and the convergence order
// of the volume of a sphere, curved against straight.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "kernels/fem/lowest_mode.hpp"
#include "kernels/fem/mesh_check.hpp"
#include "kernels/fem/object_mesh.hpp"
#include "kernels/fem/smooth_surface.hpp"
#include "test_meshes.hpp"
#include "tests/reference/lamb_sphere.hpp"

namespace {
using namespace clatter::kernels::fem;
using clatter::io::TriangleMesh;

// Element volumes summed, curved (the mesh's mid-nodes) or straight (the vertices' midpoints).
double mesh_volume(const ObjectMesh& m, bool curved) {
  double v = 0;
  for (const auto& e : m.mesh.elements) {
    Tet10Coords x;
    for (int i = 0; i < kTet10Nodes; ++i) x.col(i) = m.mesh.nodes_m.col(e[i]);
    v += tet10_volume_m3(curved ? x : tet10_straight(x.leftCols<4>()));
  }
  return v;
}

// The area of the quadratic boundary faces, by the 7-point degree-5 rule (Dunavant) per face.
double boundary_area(const ObjectMesh& m) {
  static constexpr double a1 = 0.059715871789770, b1 = 0.470142064105115, a2 = 0.797426985353087,
                          b2 = 0.101286507323456;
  static constexpr double points[7][3] = {{1. / 3, 1. / 3, 0.225},     {a1, b1, 0.132394152788506},
                                          {b1, a1, 0.132394152788506}, {b1, b1, 0.132394152788506},
                                          {a2, b2, 0.125939180544827}, {b2, a2, 0.125939180544827},
                                          {b2, b2, 0.125939180544827}};
  double area = 0;
  for (const auto& f : m.boundary) {
    Eigen::Matrix<double, 3, 6> x;
    for (int i = 0; i < 6; ++i) x.col(i) = m.mesh.nodes_m.col(f[i]);
    for (const auto& p : points) {
      const double s = p[0], t = p[1], u = 1 - s - t;  // weights of vertices 1, 2, 0
      // d/ds and d/dt of the 6-node shape functions (vertices 0, 1, 2, mid-nodes 01, 12, 20).
      const Eigen::Matrix<double, 6, 1> ds{-(4 * u - 1), 4 * s - 1, 0, 4 * (u - s), 4 * t, -4 * t};
      const Eigen::Matrix<double, 6, 1> dt{-(4 * u - 1), 0, 4 * t - 1, -4 * s, 4 * s, 4 * (u - t)};
      area += 0.5 * p[2] * (x * ds).cross(x * dt).norm();
    }
  }
  return area;
}

// Closed and consistently oriented: every boundary edge in two faces, once each way; and every
// face's normal away from the element behind it (the mesh's centroid side is not enough for a
// non-convex body, so the check is the outward volume: sum of x . n dA / 3 equals the volume).
void expect_closed(const ObjectMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : m.boundary)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    ASSERT_EQ(n, 1) << "edge " << e.first << "-" << e.second;
    ASSERT_EQ(directed.count({e.second, e.first}), 1u) << "edge " << e.first << "-" << e.second;
  }
}

ObjectMesh timed_mesh(const char* what, const TriangleMesh& s, const ObjectMeshSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  ObjectMesh m = mesh_object(s.vertices_m, s.triangles, settings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const MeshQuality& q = m.quality;
  std::printf(
      "%s: %zu input triangles, h %.4g m, thickness %.4g m, %lld elements, %lld nodes, %zu boundary faces, "
      "%lld curved and %lld sharp boundary edges, radius-edge max %.3f, dihedral %.2f..%.2f deg, Jacobian ratio "
      "min %.3f, %.2f s\n",
      what, s.triangles.size(), q.edge_length_m, m.min_thickness_m, q.elements, q.nodes, m.boundary.size(),
      static_cast<long long>(m.curved_edges), static_cast<long long>(m.sharp_edges), q.max_radius_edge,
      q.min_dihedral_deg, q.max_dihedral_deg, q.min_jacobian_ratio, seconds);
  return m;
}

void expect_within_bounds(const ObjectMesh& m) {
  const EllipsoidMeshBounds b;
  EXPECT_GT(m.quality.min_jacobian_ratio, b.min_jacobian_ratio);
  EXPECT_LE(m.quality.max_radius_edge, b.max_radius_edge);
  EXPECT_GE(m.quality.min_dihedral_deg, b.min_dihedral_deg);
}

TEST(ObjectMesh, SphereIsCurvedCloseAndDeterministic) {
  const double r = 0.1;
  const TriangleMesh s = clatter::test::icosphere(r, 2);  // 320 triangles, edges ~0.31 r
  ObjectMeshSettings settings;
  settings.edge_length_m = 0.02;
  const ObjectMesh m = timed_mesh("sphere", s, settings);
  expect_within_bounds(m);
  expect_closed(m);
  EXPECT_EQ(m.sharp_edges, 0);
  EXPECT_GT(m.curved_edges, 0);
  EXPECT_NEAR(m.min_thickness_m, 2 * r, 0.05 * r);  // the inscribed polyhedron's: 1.8 % short
  const double exact_v = 4.0 / 3 * std::numbers::pi * r * r * r, exact_a = 4 * std::numbers::pi * r * r;
  const double v_curved = mesh_volume(m, true), v_straight = mesh_volume(m, false), area = boundary_area(m);
  std::printf("sphere: volume error curved %.3g, straight %.3g, input polyhedron %.3g; area error %.3g\n",
              v_curved / exact_v - 1, v_straight / exact_v - 1,
              check_object_surface(s.vertices_m, s.triangles) / exact_v - 1, area / exact_a - 1);
  EXPECT_LT(std::abs(v_curved / exact_v - 1), 2e-3);
  EXPECT_LT(std::abs(area / exact_a - 1), 2e-3);
  // Every rank meshes the same object: bit for bit the same.
  const ObjectMesh again = mesh_object(s.vertices_m, s.triangles, settings);
  EXPECT_EQ(again.mesh.elements, m.mesh.elements);
  EXPECT_TRUE((again.mesh.nodes_m.array() == m.mesh.nodes_m.array()).all());
  EXPECT_EQ(again.boundary, m.boundary);
}

// A box's faces are flat and its edges sharp: nothing curves, volume and area are exact.
TEST(ObjectMesh, BoxStaysExact) {
  const std::array<double, 3> size{0.3, 0.2, 0.1};
  ObjectMeshSettings settings;
  settings.edge_length_m = 0.04;
  const ObjectMesh m = timed_mesh("box", clatter::test::box(size), settings);
  expect_within_bounds(m);
  expect_closed(m);
  EXPECT_EQ(m.curved_edges, 0);
  EXPECT_GT(m.sharp_edges, 0);
  EXPECT_NEAR(m.min_thickness_m, 0.1, 1e-12);
  EXPECT_NEAR(m.quality.edge_length_m, 0.1 / 3, 1e-12);
  const double v = size[0] * size[1] * size[2], a = 2 * (size[0] * size[1] + size[1] * size[2] + size[2] * size[0]);
  EXPECT_NEAR(mesh_volume(m, true), v, 1e-12 * v);
  EXPECT_NEAR(boundary_area(m), a, 1e-12 * a);
}

// The mean length of the elements' straight edges (vertex to vertex).
double mean_edge_m(const ObjectMesh& m) {
  double sum = 0;
  for (const auto& e : m.mesh.elements)
    for (const auto& k : kTet10Edges) sum += (m.mesh.nodes_m.col(e[k[0]]) - m.mesh.nodes_m.col(e[k[1]])).norm();
  return sum / (6.0 * static_cast<double>(m.mesh.elements.size()));
}

// A disk of thickness / diameter 1/40: the size follows the thickness, not edge_length_m.
TEST(ObjectMesh, ThinDiskGetsElementsThroughItsThickness) {
  const double r = 0.1, t = 0.005;
  ObjectMeshSettings settings;
  settings.edge_length_m = 0.05;
  settings.elements_through_thickness = 2;  // 3 works too: 3.4 times the elements (see the report)
  const TriangleMesh disk = clatter::test::cylinder(r, t, 64, 1);
  const ObjectMesh m = timed_mesh("disk", disk, settings);
  expect_within_bounds(m);
  expect_closed(m);
  EXPECT_NEAR(m.min_thickness_m, t, 1e-9);
  EXPECT_NEAR(m.quality.edge_length_m, t / 2, 1e-9);
  EXPECT_GT(m.sharp_edges, 0);   // the rims
  EXPECT_GT(m.curved_edges, 0);  // the side
  // Edges through the thickness: the thickness over the mean edge.
  const double across = t / mean_edge_m(m);
  std::printf("disk: mean edge %.4g m, %.2f edges through the thickness\n", mean_edge_m(m), across);
  EXPECT_GT(across, 1.6);
  EXPECT_LT(across, 3.5);
  const double v_polygon = check_object_surface(disk.vertices_m, disk.triangles), v = mesh_volume(m, true);
  const double v_cylinder = std::numbers::pi * r * r * t;
  std::printf("disk: volume %.6g m^3, input polygon %.6g (error %.3g), cylinder %.6g (error %.3g)\n", v, v_polygon,
              v / v_polygon - 1, v_cylinder, v / v_cylinder - 1);
  // The side bulges out of the 64-gon towards the circle (only partly: the rims stay straight).
  EXPECT_GT(v, v_polygon);
  EXPECT_LT(v, v_cylinder);
}

TEST(ObjectMesh, SlenderBar) {
  const std::array<double, 3> size{0.4, 0.02, 0.02};
  ObjectMeshSettings settings;
  settings.edge_length_m = 0.05;
  const ObjectMesh m = timed_mesh("bar", clatter::test::box(size), settings);
  expect_within_bounds(m);
  expect_closed(m);
  EXPECT_EQ(m.curved_edges, 0);
  EXPECT_NEAR(m.quality.edge_length_m, 0.02 / 3, 1e-12);
  EXPECT_NEAR(mesh_volume(m, true), size[0] * size[1] * size[2], 1e-12 * size[0] * size[1] * size[2]);
  const double across = 0.02 / mean_edge_m(m);
  std::printf("bar: mean edge %.4g m, %.2f edges through the thickness\n", mean_edge_m(m), across);
  EXPECT_GT(across, 2.5);
}

// A hollow ball: the inner wall wound inward is a cavity, which TetGen leaves empty.
TEST(ObjectMesh, HollowBallKeepsItsCavity) {
  const double r_out = 0.1, r_in = 0.07;
  TriangleMesh s = clatter::test::icosphere(r_out, 2);
  const TriangleMesh inner = clatter::test::icosphere(r_in, 2);
  const int offset = static_cast<int>(s.vertices_m.size());
  s.vertices_m.insert(s.vertices_m.end(), inner.vertices_m.begin(), inner.vertices_m.end());
  for (const auto& t : inner.triangles) s.triangles.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
  ObjectMeshSettings settings;
  settings.edge_length_m = 0.02;
  const ObjectMesh m = timed_mesh("hollow ball", s, settings);
  expect_within_bounds(m);
  expect_closed(m);
  EXPECT_NEAR(m.min_thickness_m, r_out - r_in, 0.1 * (r_out - r_in));
  const double v = 4.0 / 3 * std::numbers::pi * (std::pow(r_out, 3) - std::pow(r_in, 3));
  const double a = 4 * std::numbers::pi * (r_out * r_out + r_in * r_in);
  std::printf("hollow ball: volume error %.3g, area error %.3g\n", mesh_volume(m, true) / v - 1,
              boundary_area(m) / a - 1);
  EXPECT_NEAR(mesh_volume(m, true), v, 5e-3 * v);
  EXPECT_NEAR(boundary_area(m), a, 5e-3 * a);
}

// A rod as CAD exports one: its side two triangles 30 cm long and 2.6 mm wide per segment, curved.
// Bisection leaves rows of points along their diagonals; the smoothing and flips clear them.
TEST(ObjectMesh, SlenderRodOfLongThinTriangles) {
  const double r = 0.01, length = 0.3;
  ObjectMeshSettings settings;
  settings.edge_length_m = 0.05;
  const TriangleMesh rod = clatter::test::cylinder(r, length, 24, 1);
  const ObjectMesh m = timed_mesh("rod", rod, settings);
  expect_within_bounds(m);
  expect_closed(m);
  EXPECT_EQ(m.sharp_edges, 48);  // the two rims, 24 segments each: straight, never split (h > their 2.6 mm)
  EXPECT_GT(m.curved_edges, 0);
  const double v = mesh_volume(m, true), v_polygon = check_object_surface(rod.vertices_m, rod.triangles);
  const double v_cylinder = std::numbers::pi * r * r * length;
  std::printf("rod: volume %.6g m^3, input polygon error %.3g, cylinder error %.3g\n", v, v / v_polygon - 1,
              v / v_cylinder - 1);
  EXPECT_GT(v, v_polygon);
  EXPECT_LT(v, v_cylinder);
}

// The volume of a sphere from icosphere inputs of edge ~h, meshed at h: the curved boundary's
// error against the sphere falls as a higher power of h than the straight one's.
TEST(ObjectMesh, SphereVolumeConvergesFasterCurved) {
  const double r = 0.1, exact = 4.0 / 3 * std::numbers::pi * r * r * r;
  std::vector<double> h, curved, straight;
  for (int level = 1; level <= 4; ++level) {
    const TriangleMesh s = clatter::test::icosphere(r, level);
    double longest = 0;
    for (const auto& f : s.triangles)
      for (int k = 0; k < 3; ++k) {
        const auto &p = s.vertices_m[f[k]], &q = s.vertices_m[f[(k + 1) % 3]];
        longest = std::max(longest, std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
      }
    ObjectMeshSettings settings;
    settings.edge_length_m = longest;
    const ObjectMesh m = mesh_object(s.vertices_m, s.triangles, settings);
    expect_within_bounds(m);
    h.push_back(longest);
    curved.push_back(std::abs(mesh_volume(m, true) / exact - 1));
    straight.push_back(std::abs(mesh_volume(m, false) / exact - 1));
    std::printf("sphere level %d: h %.4g m, %lld elements, volume error curved %.3g, straight %.3g\n", level, longest,
                m.quality.elements, curved.back(), straight.back());
  }
  for (std::size_t i = 1; i < h.size(); ++i) {
    const double dh = std::log(h[i - 1] / h[i]);
    const double order_curved = std::log(curved[i - 1] / curved[i]) / dh,
                 order_straight = std::log(straight[i - 1] / straight[i]) / dh;
    std::printf("sphere: order curved %.2f, straight %.2f\n", order_curved, order_straight);
    EXPECT_NEAR(order_straight, 2, 0.3);
    EXPECT_GT(order_curved, 3);
  }
}

// The volume inside the smooth surface of a mesh: each patch sampled on an n x n grid of its
// barycentric coordinates, the polyhedron's volume (O(1/n^2) off), then Richardson from n and 2n.
double smooth_volume_m3(const TriangleMesh& s, double smooth_dihedral_deg) {
  const SmoothSurface surface(s.vertices_m, s.triangles, smooth_dihedral_deg);
  auto sampled = [&](int n) {
    double six_v = 0;
    for (int t = 0; t < static_cast<int>(s.triangles.size()); ++t) {
      auto at = [&](int i, int j) {
        const auto p = surface.point(t, {1.0 - double(i + j) / n, double(i) / n, double(j) / n});
        return Eigen::Vector3d(p[0], p[1], p[2]);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
          six_v += at(i, j).dot(at(i + 1, j).cross(at(i, j + 1)));
          if (i + j + 2 <= n) six_v += at(i + 1, j).dot(at(i + 1, j + 1).cross(at(i, j + 1)));
        }
    }
    return six_v / 6;
  };
  return (4 * sampled(128) - sampled(64)) / 3;
}

// One coarse input (an icosahedron split once: 80 triangles, edges 0.62 r) meshed ever finer:
// the mesh converges to the smooth surface through it, curved faster than straight.
TEST(ObjectMesh, CoarseInputConvergesToItsSmoothSurface) {
  const double r = 0.1;
  const TriangleMesh s = clatter::test::icosphere(r, 1);
  const double exact = smooth_volume_m3(s, 30);
  std::printf("coarse sphere: smooth surface's volume %.3g of the sphere's off\n",
              exact / (4.0 / 3 * std::numbers::pi * r * r * r) - 1);
  std::vector<double> h{0.04, 0.02, 0.01}, curved, straight;
  for (double h_m : h) {
    ObjectMeshSettings settings;
    settings.edge_length_m = h_m;
    const ObjectMesh m = mesh_object(s.vertices_m, s.triangles, settings);
    expect_within_bounds(m);
    curved.push_back(std::abs(mesh_volume(m, true) / exact - 1));
    straight.push_back(std::abs(mesh_volume(m, false) / exact - 1));
    std::printf("coarse sphere: h %.3g m, %lld elements, volume error curved %.3g, straight %.3g\n", h_m,
                m.quality.elements, curved.back(), straight.back());
  }
  for (std::size_t i = 1; i < h.size(); ++i) {
    const double dh = std::log(h[i - 1] / h[i]);
    const double order_curved = std::log(curved[i - 1] / curved[i]) / dh,
                 order_straight = std::log(straight[i - 1] / straight[i]) / dh;
    std::printf("coarse sphere: order curved %.2f, straight %.2f\n", order_curved, order_straight);
    EXPECT_NEAR(order_straight, 2, 0.4);
    // O(h^3) at first; then O(h^2) with a 600 times smaller constant: the PN patches meet with a
    // small kink in their normals, and elements across an input edge (after the flips and
    // smoothing) cut it.
    EXPECT_GT(order_curved, 1.8);
    EXPECT_LT(curved[i], straight[i] / 100);
  }
}

// The lowest free mode of a glass sphere (Lamb's T2) on meshes of one 320-triangle icosphere: the
// curved mesh of its smooth surface, and the flat one of the polyhedron (smooth_dihedral_deg 0).
TEST(ObjectMesh, SphereLambFrequencyCurvedAgainstFlat) {
  const double r = 0.1;
  clatter::model::Material glass;
  glass.youngs_pa = 6.2e10, glass.poisson = 0.2, glass.rho_kg_m3 = 2600;
  const auto t2 = clatter::reference::lamb_sphere_modes(glass.poisson, 4.0).at(0);
  const double lamb_hz = clatter::reference::lamb_frequency_hz(t2, r, glass.youngs_pa, glass.poisson, glass.rho_kg_m3);
  const TriangleMesh s = clatter::test::icosphere(r, 2);
  double error[2] = {0, 0};
  for (int curved = 0; curved < 2; ++curved) {
    ObjectMeshSettings settings;
    settings.edge_length_m = 0.04;
    settings.smooth_dihedral_deg = curved ? 30 : 0;
    const ObjectMesh m = mesh_object(s.vertices_m, s.triangles, settings);
    const LowestMode mode = lowest_free_mode_of(m.mesh, glass);
    error[curved] = mode.frequency_hz / lamb_hz - 1;
    std::printf("sphere T2 %s: %lld elements, f %.6g Hz, Lamb %.6g Hz, error %.3g\n", curved ? "curved" : "flat",
                m.quality.elements, mode.frequency_hz, lamb_hz, error[curved]);
  }
  EXPECT_LT(std::abs(error[1]), 2e-3);
  EXPECT_LT(std::abs(error[1]), std::abs(error[0]) / 4);
}

}  // namespace
