// The object bank's input checks (kernels/fem/mesh_check.*): each bad mesh refused with its reason,
// naming the triangle or edge; the scale warning for a mesh in millimetres read as metres.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "kernels/fem/mesh_check.hpp"
#include "test_meshes.hpp"

namespace {
using namespace clatter::kernels::fem;
using clatter::io::TriangleMesh;

// The reason check_object_surface gives, or "" where it accepts the mesh.
std::string refusal(const TriangleMesh& m) {
  try {
    check_object_surface(m.vertices_m, m.triangles);
  } catch (const SurfaceError& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_REASON(mesh, text)                                              \
  do {                                                                         \
    const std::string why = refusal(mesh);                                     \
    EXPECT_NE(why.find(text), std::string::npos) << "reason: '" << why << "'"; \
  } while (0)

// Two meshes as one, vertices at the same place welded into one.
TriangleMesh weld(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh out;
  std::map<std::array<double, 3>, int> index;
  for (const TriangleMesh* m : {&a, &b})
    for (const auto& t : m->triangles) {
      std::array<int, 3> f{};
      for (int k = 0; k < 3; ++k) {
        const auto& p = m->vertices_m[t[k]];
        const auto [it, fresh] = index.try_emplace(p, static_cast<int>(out.vertices_m.size()));
        if (fresh) out.vertices_m.push_back(p);
        f[k] = it->second;
      }
      out.triangles.push_back(f);
    }
  return out;
}

TriangleMesh shifted(TriangleMesh m, std::array<double, 3> by_m) {
  for (auto& p : m.vertices_m)
    for (int k = 0; k < 3; ++k) p[k] += by_m[k];
  return m;
}

TEST(MeshCheck, AcceptsClosedSolids) {
  EXPECT_EQ(refusal(clatter::test::icosphere(0.1, 2)), "");
  EXPECT_EQ(refusal(clatter::test::box({0.3, 0.2, 0.1}, 2)), "");
  EXPECT_EQ(refusal(clatter::test::cylinder(0.1, 0.005, 48, 1)), "");
  // A hollow ball: the inner surface wound inward is a cavity, not a second body.
  TriangleMesh inner = clatter::test::icosphere(0.05, 2);
  for (auto& t : inner.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(refusal(weld(clatter::test::icosphere(0.1, 2), inner)), "");
  const TriangleMesh cube = clatter::test::box({1, 1, 1});
  EXPECT_DOUBLE_EQ(check_object_surface(cube.vertices_m, cube.triangles), 1.0);
}

TEST(MeshCheck, RefusesAnOpenBox) {
  TriangleMesh m = clatter::test::box({1, 1, 1}, 2);
  m.triangles.pop_back();
  EXPECT_REASON(m, "the surface is open: edge (");
  EXPECT_REASON(m, "bounds one triangle only");
}

TEST(MeshCheck, RefusesTwoCubesSharingAnEdge) {
  const TriangleMesh m = weld(clatter::test::box({1, 1, 1}), shifted(clatter::test::box({1, 1, 1}), {1, 1, 0}));
  EXPECT_REASON(m, "not manifold");
  EXPECT_REASON(m, "bounds 4 triangles");
}

TEST(MeshCheck, RefusesSelfIntersection) {
  // Two cubes that overlap: each closed, together crossing.
  const TriangleMesh pair =
      weld(clatter::test::box({1, 1, 1}), shifted(clatter::test::box({1, 1, 1}), {0.5, 0.4, 0.3}));
  EXPECT_REASON(pair, "intersects itself");
  EXPECT_REASON(pair, "triangle ");
  // One surface: the top face's centre pushed down through the bottom.
  TriangleMesh poked = clatter::test::box({1, 1, 1}, 2);
  for (auto& p : poked.vertices_m)
    if (p[0] == 0.5 && p[1] == 0.5 && p[2] == 1) p[2] = -0.5;
  EXPECT_REASON(poked, "intersects itself");
  // Two separate cubes apart: two bodies.
  EXPECT_REASON(weld(clatter::test::box({1, 1, 1}), shifted(clatter::test::box({1, 1, 1}), {3, 0, 0})),
                "2 separate parts");
}

TEST(MeshCheck, RefusesReversedWinding) {
  TriangleMesh m = clatter::test::icosphere(0.1, 1);
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  EXPECT_REASON(m, "the faces point inward");
  // One triangle reversed: inconsistent, named by its edge.
  TriangleMesh one = clatter::test::icosphere(0.1, 1);
  std::swap(one.triangles[7][1], one.triangles[7][2]);
  EXPECT_REASON(one, "not consistently oriented at edge");
}

TEST(MeshCheck, RefusesAZeroAreaTriangle) {
  // Edge (a, b) of two triangles split at its midpoint m on one side, closed by the flat (m, a, b).
  TriangleMesh m = clatter::test::icosphere(0.1, 1);
  const auto t1 = m.triangles[0];
  const int a = t1[0], b = t1[1], c = t1[2];
  const int mid = static_cast<int>(m.vertices_m.size());
  m.vertices_m.push_back({0.5 * (m.vertices_m[a][0] + m.vertices_m[b][0]),
                          0.5 * (m.vertices_m[a][1] + m.vertices_m[b][1]),
                          0.5 * (m.vertices_m[a][2] + m.vertices_m[b][2])});
  m.triangles[0] = {a, mid, c};
  m.triangles.push_back({mid, b, c});
  m.triangles.push_back({mid, a, b});
  const std::string why = refusal(m);
  EXPECT_NE(why.find("triangle " + std::to_string(m.triangles.size() - 1) + " "), std::string::npos) << why;
  EXPECT_NE(why.find("degenerate"), std::string::npos) << why;
}

TEST(MeshCheck, WarnsOfAMeshInMillimetres) {
  const TriangleMesh cup = clatter::test::icosphere(0.05, 2);  // 10 cm across
  const double steel_kg_m3 = 7850;
  const double volume = check_object_surface(cup.vertices_m, cup.triangles);
  EXPECT_EQ(implausible_scale(cup.vertices_m, volume, steel_kg_m3), "");
  TriangleMesh big = cup;
  for (auto& p : big.vertices_m)
    for (double& x : p) x *= 1000;
  const std::string why = implausible_scale(big.vertices_m, volume * 1e9, steel_kg_m3);
  EXPECT_NE(why.find("millimetres"), std::string::npos) << why;
  EXPECT_NE(why.find(" m across"), std::string::npos) << why;
  // Heavy but small (a 1 m^3 block of lead): the mass alone.
  const TriangleMesh block = clatter::test::box({1, 1, 1});
  EXPECT_NE(implausible_scale(block.vertices_m, 1.0, 11340), "");
}

}  // namespace
