// Closed triangle meshes: the OBJ reader's checks, and mass properties against closed forms that
// do not come from the mesh code: a rotated box, a non-convex L prism by the parallel-axis theorem
// over its two boxes, and the convergence of tessellated spheres to the solid sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "kernels/mass_properties.hpp"

namespace {

using clatter::kernels::Mat3;
using clatter::Vec3;
using Triangles = std::vector<std::array<int, 3>>;

// A box [0, a] x [0, b] x [0, c], faces wound counter-clockwise seen from outside.
void box(double a, double b, double c, std::vector<Vec3>& v, Triangles& t) {
  v.clear();
  for (int k = 0; k < 8; ++k) v.push_back({(k & 1) * a, ((k >> 1) & 1) * b, ((k >> 2) & 1) * c});
  t = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
       {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
}

Mat3 rotation(const Vec3& axis, double angle) {  // Rodrigues
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const Vec3 u{axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 r{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) r[i][j] = (i == j ? c : 0.0) + (1 - c) * u[i] * u[j];
  r[0][1] -= s * u[2]; r[0][2] += s * u[1]; r[1][0] += s * u[2];
  r[1][2] -= s * u[0]; r[2][0] -= s * u[1]; r[2][1] += s * u[0];
  return r;
}

double max_abs_diff(const Mat3& x, const Mat3& y) {
  double d = 0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) d = std::max(d, std::abs(x[i][j] - y[i][j]));
  return d;
}

TEST(MeshMassProperties, RotatedTranslatedBoxMatchesTheClosedForm) {
  const double a = 0.3, b = 0.2, c = 0.1;
  std::vector<Vec3> v;
  Triangles t;
  box(a, b, c, v, t);
  const Mat3 r = rotation({1, 2, 3}, 0.7);
  const Vec3 shift{5.0, -3.0, 2.0};  // far from the origin: no digits lost
  for (auto& p : v) {
    const Vec3 q = p;
    for (std::size_t i = 0; i < 3; ++i) p[i] = shift[i] + r[i][0] * q[0] + r[i][1] * q[1] + r[i][2] * q[2];
  }
  const auto m = clatter::kernels::mesh_mass_properties(v, t);
  const double vol = a * b * c;
  EXPECT_NEAR(m.volume_m3, vol, 1e-15);
  // Centre: R (a, b, c) / 2 + shift.  Inertia: R diag(V (b^2 + c^2) / 12, ...) R^T.
  const Vec3 d{vol * (b * b + c * c) / 12, vol * (a * a + c * c) / 12, vol * (a * a + b * b) / 12};
  Mat3 expected{};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(m.centroid_m[i], shift[i] + (r[i][0] * a + r[i][1] * b + r[i][2] * c) / 2, 1e-13);
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t k = 0; k < 3; ++k) expected[i][j] += r[i][k] * d[k] * r[j][k];
  }
  EXPECT_LT(max_abs_diff(m.inertia_per_density_m5, expected), 1e-12 * d[2]);
}

TEST(MeshMassProperties, NonConvexPrismEqualsItsTwoBoxesByParallelAxes) {
  // The L-shaped prism {[0,2]x[0,1] U [0,1]x[1,2]} x [0,h]: its cap is fanned from the reflex
  // corner (1,1); the sides are quads.
  const double h = 0.5;
  const std::vector<std::array<double, 2>> ring{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // counter-clockwise
  std::vector<Vec3> v;
  for (double z : {0.0, h})
    for (const auto& p : ring) v.push_back({p[0], p[1], z});
  Triangles t;
  const int n = 6;
  for (int k : {4, 5, 0, 1}) {  // fan from corner 3 over the edges (4,5), (5,0), (0,1), (1,2)
    t.push_back({3, (k + 1) % n, k});            // bottom, seen from below
    t.push_back({n + 3, n + k, n + (k + 1) % n});  // top
  }
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1) % n;
    t.push_back({k, k1, n + k1});
    t.push_back({k, n + k1, n + k});
  }
  const auto m = clatter::kernels::mesh_mass_properties(v, t);
  // Box 1: [0,2]x[0,1]x[0,h], box 2: [0,1]x[1,2]x[0,h], each moved to the union's centre.
  struct Box { double lx, ly, cx, cy; };
  const Box boxes[2] = {{2, 1, 1, 0.5}, {1, 1, 0.5, 1.5}};
  double vol = 0, cx = 0, cy = 0;
  for (const auto& bx : boxes) {
    const double vb = bx.lx * bx.ly * h;
    vol += vb;
    cx += vb * bx.cx;
    cy += vb * bx.cy;
  }
  cx /= vol;
  cy /= vol;
  Mat3 expected{};
  for (const auto& bx : boxes) {
    const double vb = bx.lx * bx.ly * h, dx = bx.cx - cx, dy = bx.cy - cy;
    expected[0][0] += vb * (bx.ly * bx.ly + h * h) / 12 + vb * dy * dy;
    expected[1][1] += vb * (bx.lx * bx.lx + h * h) / 12 + vb * dx * dx;
    expected[2][2] += vb * (bx.lx * bx.lx + bx.ly * bx.ly) / 12 + vb * (dx * dx + dy * dy);
    expected[0][1] -= vb * dx * dy;
  }
  expected[1][0] = expected[0][1];
  EXPECT_NEAR(m.volume_m3, vol, 1e-14);
  EXPECT_NEAR(m.centroid_m[0], cx, 1e-14);
  EXPECT_NEAR(m.centroid_m[1], cy, 1e-14);
  EXPECT_NEAR(m.centroid_m[2], h / 2, 1e-14);
  EXPECT_LT(max_abs_diff(m.inertia_per_density_m5, expected), 1e-13);
  EXPECT_GT(expected[0][1], 0.01);  // the product of inertia is really exercised
  // Turned inside out: the same solid with negative volume.
  for (auto& tri : t) std::swap(tri[1], tri[2]);
  EXPECT_NEAR(clatter::kernels::mesh_mass_properties(v, t).volume_m3, -vol, 1e-14);
}

// An icosahedron subdivided `levels` times, vertices pushed to the sphere of radius r.
void icosphere(int levels, double r, std::vector<Vec3>& v, Triangles& t) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
       {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  t = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
       {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
       {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  auto project = [&](Vec3 p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (auto& x : p) x *= r / n;
    return p;
  };
  for (auto& p : v) p = project(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int i, int j) {
      const auto key = std::minmax(i, j);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      const auto& a = v[static_cast<std::size_t>(i)];
      const auto& b = v[static_cast<std::size_t>(j)];
      v.push_back(project({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2}));
      return mid[key] = static_cast<int>(v.size() - 1);
    };
    Triangles finer;
    for (const auto& f : t) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    t = finer;
  }
}

TEST(MeshMassProperties, TessellatedSpheresConvergeToTheSolidSphereAtSecondOrder) {
  // An inscribed polyhedron with edges ~h misses a shell of depth ~h^2: volume and moments
  // converge at order 2 in h, which halves with each subdivision (error ratio ~4).
  const double r = 0.2, vol = 4.0 / 3.0 * std::numbers::pi * r * r * r, moment = 0.4 * vol * r * r;
  double previous_v = 0, previous_i = 0;
  for (int level = 1; level <= 5; ++level) {
    std::vector<Vec3> v;
    Triangles t;
    icosphere(level, r, v, t);
    const auto m = clatter::kernels::mesh_mass_properties(v, t);
    const double ev = std::abs(m.volume_m3 - vol) / vol;
    double ei = 0;
    for (std::size_t i = 0; i < 3; ++i) {
      ei = std::max(ei, std::abs(m.inertia_per_density_m5[i][i] - moment) / moment);
      EXPECT_LT(std::abs(m.centroid_m[i]), 1e-15);
    }
    if (level > 1) {
      EXPECT_NEAR(previous_v / ev, 4.0, 0.5) << "level " << level;
      EXPECT_NEAR(previous_i / ei, 4.0, 0.5) << "level " << level;
      std::printf("level %d: %zu triangles, volume error %.3e (ratio %.2f), moment error %.3e (ratio %.2f)\n", level,
                  t.size(), ev, previous_v / ev, ei, previous_i / ei);
    }
    previous_v = ev;
    previous_i = ei;
  }
  EXPECT_LT(previous_v, 2e-3);
}

// ---- the OBJ reader

std::string write(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "clatter-test-mesh";
  std::filesystem::create_directories(dir);
  const auto path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

// A unit cube as 6 quads, with comments, normals and texture indices that the reader skips.
const std::string cube_obj =
    "# cube\no cube\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\nvn 0 0 1\n"
    "f 1 3 4 2\nf 5/1 6/1 8/1 7/1\nf 1//1 2//1 6//1 5//1\nf 3 7 8 4\nf 1 5 7 3\nf -7 -5 -1 -3\n";

TEST(ObjReader, ReadsPolygonsAndRelativeIndicesIntoAClosedMesh) {
  const auto mesh = clatter::io::read_obj(write("cube.obj", cube_obj));
  ASSERT_EQ(mesh.vertices_m.size(), 8u);
  ASSERT_EQ(mesh.triangles.size(), 12u);
  const auto m = clatter::kernels::mesh_mass_properties(mesh.vertices_m, mesh.triangles);
  EXPECT_NEAR(m.volume_m3, 1.0, 1e-15);
  EXPECT_NEAR(m.inertia_per_density_m5[0][0], 1.0 / 6.0, 1e-15);
}

void expect_error(const std::string& name, const std::string& text, const std::vector<std::string>& fragments) {
  const auto path = write(name, text);
  try {
    clatter::io::read_obj(path);
    ADD_FAILURE() << name << ": no error";
  } catch (const clatter::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    for (const auto& f : fragments) EXPECT_NE(what.find(f), std::string::npos) << what << " lacks " << f;
  }
}

TEST(ObjReader, RefusesMeshesThatBoundNoSolid) {
  const std::string vertices = cube_obj.substr(0, cube_obj.find("f "));
  expect_error("open.obj", vertices + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\n", {"not closed"});
  expect_error("flipped.obj", vertices + "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 6 8 4\n",
               {"inconsistently oriented"});
  expect_error("range.obj", vertices + "f 1 3 9\n", {":12:", "9"});
  expect_error("zero.obj", vertices + "f 0 1 2\n", {":12:"});
  expect_error("nan.obj", "v 0 0 nan\n", {":1:", "must be finite"});
  expect_error("text.obj", "v 0 zero 0\n", {":1:", "'zero'"});
  expect_error("repeat.obj", vertices + "f 1 1 2\n", {":12:", "repeats vertex 1"});
  expect_error("few.obj", vertices + "f 1 2 3\n", {"1 triangles"});
  EXPECT_THROW(clatter::io::read_obj("/nonexistent/mesh.obj"), clatter::InputError);
}

}  // namespace
