// Cut-cell geometry against closed-form volumes and surface integrals of the ellipsoid.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "kernels/fdtd/geometry.hpp"

using namespace clatter::kernels::fdtd;

namespace {
constexpr double kDx = 0.02;
const Ellipsoid kBody{0.3, 0.2, 0.13};

// Visits every cell centre of a symmetric grid covering the body.
template <class F>
void for_cells(F f) {
  const int n = 40;  // 40 cells of 2 cm: [-0.4, 0.4]
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) f(std::array<double, 3>{(i + 0.5 - n / 2) * kDx, (j + 0.5 - n / 2) * kDx, (k + 0.5 - n / 2) * kDx});
}
}  // namespace

TEST(CutCells, SolidVolumeIsTheEllipsoidVolume) {
  double solid = 0;
  for_cells([&](const auto& c) { solid += 1.0 - cell_geometry(kBody, c, kDx, 16).beta; });
  const double exact = 4.0 / 3.0 * M_PI * kBody.a_m * kBody.b_m * kBody.c_m / (kDx * kDx * kDx);
  EXPECT_NEAR(solid, exact, 2e-4 * exact);
}

TEST(CutCells, TranslationFluxIsTheDisplacedVolumeRate) {
  // Moving the body along x with unit speed, the net flux into the fluid over all cells of the
  // +x half is the projected area pi B C (divergence theorem); the -x half gives the opposite.
  double plus = 0, minus = 0;
  for_cells([&](const auto& c) {
    const double t = cell_geometry(kBody, c, kDx, 16).body_flux[0];
    (c[0] > 0 ? plus : minus) += t;
  });
  const double area = M_PI * kBody.b_m * kBody.c_m / (kDx * kDx);
  EXPECT_NEAR(plus, -area, 3e-3 * area);  // outward normals of fluid cells point into the body
  EXPECT_NEAR(minus, area, 3e-3 * area);
}

TEST(CutCells, RotationOfASphereDisplacesNothing) {
  const Ellipsoid sphere{0.25, 0.25, 0.25};
  double largest = 0, total_abs = 0;
  for_cells([&](const auto& c) {
    const auto g = cell_geometry(sphere, c, kDx, 16);
    for (int f = 3; f < 6; ++f) {
      largest = std::max(largest, std::abs(g.body_flux[f]));
      total_abs += std::abs(g.body_flux[f]);
    }
  });
  // Per cell: (e x r).n = 0 on the sphere, so only sampling error remains (cell units of length).
  EXPECT_LT(largest / (0.25 / kDx), 2e-3);
  EXPECT_GT(total_abs, 0.0);
}

TEST(CutCells, MirroredCellsAreExactMirrors) {
  const std::array<double, 3> c{0.27, -0.05, 0.11};
  const auto g = cell_geometry(kBody, c, kDx, 16);
  for (int axis = 0; axis < 3; ++axis) {
    auto m = c;
    m[axis] = -m[axis];
    const auto h = cell_geometry(kBody, m, kDx, 16);
    EXPECT_EQ(g.beta, h.beta);
    EXPECT_EQ(g.alpha[2 * axis], h.alpha[2 * axis + 1]);
    for (int f = 0; f < 6; ++f) EXPECT_EQ(h.body_flux[f], field_parity(f + 1, axis) * g.body_flux[f]) << axis << f;
  }
}

TEST(CutCells, SharedFacesAgree) {
  // The face between two neighbours has one fluid fraction, seen from either side.
  for (double y : {-0.07, 0.01, 0.09})
    for (double x = -0.31; x < 0.31; x += kDx) {
      const auto left = cell_geometry(kBody, {x, y, 0.05}, kDx, 16);
      const auto right = cell_geometry(kBody, {x + kDx, y, 0.05}, kDx, 16);
      EXPECT_NEAR(left.alpha[1], right.alpha[0], 1e-12);
    }
}

// ---- bodies given as closed triangle meshes (kernels/fdtd/mesh_body.hpp)

#include "kernels/fdtd/mesh_body.hpp"
#include "kernels/mass_properties.hpp"
#include "tests/reference/test_meshes.hpp"

namespace {
using clatter::reference::Mesh;

MeshBody body_of(const Mesh& m) { return MeshBody(m.vertices, m.triangles); }

// Number of the cells' sample lines (step kDx / 16, at odd multiples of step / 2 from the origin)
// with |coordinate| < h: the sampled extent of [-h, h] along a sampled axis is that times step.
int samples_within(double h, double step) {
  int n = 0;
  for (int k = -1000; k < 1000; ++k) n += std::abs((k + 0.5) * step) < h;
  return n;
}
}  // namespace

TEST(MeshCutCells, BoxVolumeIsExactlyItsSampledVolume) {
  // An axis-aligned box with faces between sample lines: every z line is solid over exactly
  // [-hz, hz] or not at all, so the cells' solid volume is the product of the sampled extents in x
  // and y and the exact 2 hz, to rounding. Lines through the diagonals of the +-z faces (x = y)
  // exercise the tie rule: a double or missed crossing there would change the sum by a line's share.
  const double hx = 0.1037, hy = 0.0713, hz = 0.0529, step = kDx / 16;
  const MeshBody box = body_of(clatter::reference::box_mesh(hx, hy, hz));
  EXPECT_TRUE(box.mirror_symmetric());
  double solid = 0;
  long inside = 0, outside = 0;
  for_cells([&](const auto& c) {
    const auto g = cell_geometry(box, c, kDx, 16);
    solid += (1.0 - g.beta) * kDx * kDx * kDx;
    const bool in = std::abs(c[0]) + kDx / 2 < hx && std::abs(c[1]) + kDx / 2 < hy && std::abs(c[2]) + kDx / 2 < hz;
    const bool out = std::abs(c[0]) - kDx / 2 > hx || std::abs(c[1]) - kDx / 2 > hy || std::abs(c[2]) - kDx / 2 > hz;
    if (in) {
      ++inside;
      EXPECT_EQ(g.beta, 0.0);
      for (double a : g.alpha) EXPECT_EQ(a, 0.0);
    }
    if (out) {
      ++outside;
      EXPECT_EQ(g.beta, 1.0);
      for (double a : g.alpha) EXPECT_EQ(a, 1.0);
      for (double f : g.body_flux) EXPECT_EQ(f, 0.0);
    }
  });
  const double sampled = samples_within(hx, step) * step * samples_within(hy, step) * step * 2 * hz;
  const double exact = 8 * hx * hy * hz;
  std::printf("box: solid volume %.12g m^3, sampled extents give %.12g, exact %.12g (%ld cells inside, %ld outside)\n",
              solid, sampled, exact, inside, outside);
  EXPECT_GT(inside, 0);
  EXPECT_NEAR(solid, sampled, 1e-12 * exact);
  // Each sampled extent is within one step of the exact one.
  EXPECT_NEAR(solid, exact, exact * (step / hx + step / hy));
}

TEST(MeshCutCells, IcosphereVolumeIsTheMeshVolume) {
  // The midpoint rule over (x, y) with exact chords along z is exact where the chord length is
  // linear in (x, y), i.e. away from projected edges and the silhouette; there its error has both
  // signs. For a polyhedron approximating a sphere the sampled surface is the same as the analytic
  // sphere's to within the polygonization, so the analytic ellipsoid's bound (2e-4, above) holds.
  const Mesh m = clatter::reference::icosphere(0.25, 4);
  const MeshBody sphere = body_of(m);
  EXPECT_TRUE(sphere.mirror_symmetric());
  double solid = 0;
  for_cells([&](const auto& c) { solid += (1.0 - cell_geometry(sphere, c, kDx, 16).beta) * kDx * kDx * kDx; });
  const double exact = clatter::kernels::mesh_mass_properties(m.vertices, m.triangles).volume_m3;
  std::printf("icosphere (5120 triangles): solid volume %.9g m^3, mesh volume %.9g: relative %.2e\n", solid, exact,
              solid / exact - 1);
  EXPECT_NEAR(solid, exact, 2e-4 * exact);
  EXPECT_NEAR(sphere.volume_m3(), exact, 1e-12 * exact);
}

TEST(MeshCutCells, EllipsoidMeshAgreesWithTheAnalyticEllipsoid) {
  // An icosphere scaled to kBody is inscribed in it (vertices on the surface, flat facets inside,
  // both convex), so along every sample line its chord lies within the ellipsoid's: per cell the
  // mesh's fluid fractions can only be larger, and the total difference is the volume between the
  // two surfaces (both sampled on the same lines). The shell's thickness is the polygonization
  // error: 1 - (distance of the nearest facet plane from the centre) on the unit sphere, times A.
  const Mesh m = clatter::reference::icosphere(1.0, 5, kBody.a_m, kBody.b_m, kBody.c_m);
  const MeshBody mesh = body_of(m);
  const double mesh_volume = mesh.volume_m3();
  const double ellipsoid_volume = 4.0 / 3.0 * M_PI * kBody.a_m * kBody.b_m * kBody.c_m;
  const Mesh unit = clatter::reference::icosphere(1.0, 5);
  double nearest = 1;
  for (const auto& t : unit.triangles) {
    const auto& a = unit.vertices[t[0]];
    const auto& b = unit.vertices[t[1]];
    const auto& c = unit.vertices[t[2]];
    const std::array<double, 3> e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    nearest = std::min(nearest, std::abs(n[0] * a[0] + n[1] * a[1] + n[2] * a[2]) / std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
  }
  const double shell_m = (1 - nearest) * kBody.a_m;
  double difference = 0, largest = 0, below = 0;
  for_cells([&](const auto& c) {
    const auto gm = cell_geometry(mesh, c, kDx, 16), ge = cell_geometry(kBody, c, kDx, 16);
    below = std::max(below, ge.beta - gm.beta);
    for (int f = 0; f < 6; ++f) below = std::max(below, ge.alpha[f] - gm.alpha[f]);
    difference += (gm.beta - ge.beta) * kDx * kDx * kDx;
    largest = std::max(largest, gm.beta - ge.beta);
  });
  std::printf("ellipsoid mesh (20480 triangles, shell %.3g mm = %.3g cells): sum of (beta_mesh - beta_ell) dx^3 = "
              "%.5g m^3, volume between the surfaces %.5g m^3; largest per cell %.3g; largest the other way %.2g\n",
              shell_m * 1e3, shell_m / kDx, difference, ellipsoid_volume - mesh_volume, largest, below);
  EXPECT_LT(below, 1e-12);
  EXPECT_NEAR(difference, ellipsoid_volume - mesh_volume, 0.1 * (ellipsoid_volume - mesh_volume));
  // A cell holds at most ~3 dx^2 of surface, under a shell of this thickness.
  EXPECT_LT(largest, 3 * shell_m / kDx);
}

namespace {
// Divergence theorem for the rigid fields (div g = 0): summed over a set S of whole cells, the body
// flux of field i is the integral of g_i . n (n out of S) over the solid part of S's boundary (the
// cells' shared faces cancel). For S = the cells beyond the plane x[a] = at (n = -e_a there), it is
// minus the integral of g_i . e_a over the body's section by that plane: -A for the translation
// along a, 0 for the others, and -(e_k x M)_a for the rotation about e_k, M the section's first
// moment. For S = every cell, 0.
void check_divergence(const Mesh& mesh_in, const char* name) {
  const MeshBody body = body_of(mesh_in);
  const Mesh centred{body.vertices_m(), body.triangles()};
  std::array<double, 6> everywhere{};
  double total_scale = 0;
  for (int a = 0; a < 3; ++a) {
    const double at = 2 * kDx;  // a cell boundary, through the body, on no vertex
    const auto s = clatter::reference::mesh_section(centred, a, at);
    std::array<double, 6> want{}, got{};
    want[a] = -s.area;
    for (int k = 0; k < 3; ++k) {
      const std::array<double, 3> e{double(k == 0), double(k == 1), double(k == 2)};
      const std::array<double, 3> cross{e[1] * s.moment[2] - e[2] * s.moment[1], e[2] * s.moment[0] - e[0] * s.moment[2],
                                        e[0] * s.moment[1] - e[1] * s.moment[0]};
      want[3 + k] = -cross[a];
    }
    for_cells([&](const auto& c) {
      const auto g = cell_geometry(body, c, kDx, 16);
      for (int f = 0; f < 6; ++f) {
        if (c[a] > at) got[f] += g.body_flux[f] * kDx * kDx;
        if (a == 0) {
          everywhere[f] += g.body_flux[f] * kDx * kDx;
          total_scale += std::abs(g.body_flux[f]) * kDx * kDx;
        }
      }
    });
    const double r = body.bounding_radius_m();
    for (int f = 0; f < 6; ++f) {
      // Per unit of the section's area (times the radius for the rotations): the face chords are
      // exact, the sampling across them a midpoint rule with ~1e-3 error at 16 samples a cell, as
      // for the analytic ellipsoid's translation flux above (3e-3).
      const double scale = f < 3 ? s.area : s.area * r;
      std::printf("%s, cells beyond %c = %.2f m: field %d flux %+.6e, section gives %+.6e (%.1e)\n", name, "xyz"[a], at,
                  f + 1, got[f], want[f], (got[f] - want[f]) / scale);
      EXPECT_NEAR(got[f], want[f], 3e-3 * scale) << name << " axis " << a << " field " << f + 1;
    }
  }
  for (int f = 0; f < 6; ++f) EXPECT_NEAR(everywhere[f], 0.0, 1e-12 * total_scale) << name << " field " << f + 1;
}
}  // namespace

TEST(MeshCutCells, BodyFluxObeysTheDivergenceTheorem) {
  check_divergence(clatter::reference::icosphere(0.25, 3, 1.0, 0.8, 0.6), "icosphere ellipsoid");
  check_divergence(clatter::reference::cut_cube(0.15, 0.12), "cut cube");
}

TEST(MeshCutCells, MirrorSymmetryIsDetected) {
  EXPECT_TRUE(body_of(clatter::reference::box_mesh(0.1, 0.07, 0.05)).mirror_symmetric());
  EXPECT_TRUE(body_of(clatter::reference::icosphere(0.2, 3, 1.0, 0.7, 0.5)).mirror_symmetric());
  const MeshBody cut = body_of(clatter::reference::cut_cube(0.1, 0.05));
  std::printf("cut cube: mirror mismatch %.3g of the radius\n", cut.mirror_mismatch());
  EXPECT_FALSE(cut.mirror_symmetric());
  EXPECT_EQ(cut.mirror_axes(), 0);
  EXPECT_EQ(body_of(clatter::reference::box_mesh(0.1, 0.07, 0.05)).mirror_axes(), 7);
  // Two planes of three: a square pyramid is its own image in x and y, not in z.
  const MeshBody pyramid = body_of(clatter::reference::square_pyramid(0.05, 0.06));
  EXPECT_EQ(pyramid.mirror_axes(), 3);
  EXPECT_FALSE(pyramid.mirror_symmetric());
  Mesh lying = clatter::reference::square_pyramid(0.05, 0.06);  // apex along x: y and z
  for (auto& v : lying.vertices) v = {v[2], v[1], -v[0]};
  EXPECT_EQ(body_of(lying).mirror_axes(), 6);
  // A symmetric mesh moved off its centre of mass is centred again: still symmetric.
  Mesh moved = clatter::reference::box_mesh(0.1, 0.07, 0.05);
  for (auto& v : moved.vertices) v = {v[0] + 0.3, v[1] - 0.2, v[2] + 0.01};
  const MeshBody back = body_of(moved);
  EXPECT_TRUE(back.mirror_symmetric());
  EXPECT_NEAR(back.centre_of_mass_offset_m()[0], 0.3, 1e-12);
  EXPECT_NEAR(back.centre_of_mass_offset_m()[1], -0.2, 1e-12);
}

TEST(MeshCutCells, AsymmetricMeshCellsAreComputedWhereTheyAre) {
  // No mirroring for an asymmetric body. The cube |x|, |y|, |z| <= h without its (+, +, +) corner
  // (a tetrahedron of volume cut^3 / 6), centred on its centre of mass (moved by d = -com along
  // each axis): the octant (+, +, +) holds (h + d)^3 - cut^3 / 6, the octant (-, -, -) (h - d)^3.
  // The faces x, y = +-(h +- d) fall between sample lines: each may be off by half a sample step
  // times its area; the planes x, y, z = 0 are cell faces and the z faces have exact chords.
  const double h = 0.1, cut = 0.08, step = kDx / 16;
  const MeshBody body = body_of(clatter::reference::cut_cube(h, cut));
  const double d = -body.centre_of_mass_offset_m()[0];
  double plus = 0, minus = 0;
  for_cells([&](const auto& c) {
    const double s = (1.0 - cell_geometry(body, c, kDx, 16).beta) * kDx * kDx * kDx;
    if (c[0] > 0 && c[1] > 0 && c[2] > 0) plus += s;
    if (c[0] < 0 && c[1] < 0 && c[2] < 0) minus += s;
  });
  const double want_plus = std::pow(h + d, 3) - cut * cut * cut / 6, want_minus = std::pow(h - d, 3);
  const double tol = 2 * (step / 2) * (h + d) * (h + d);
  std::printf("cut cube: octant (+,+,+) %.6g m^3 (want %.6g), (-,-,-) %.6g (want %.6g), tolerance %.2g\n", plus,
              want_plus, minus, want_minus, tol);
  EXPECT_NEAR(plus, want_plus, tol);
  EXPECT_NEAR(minus, want_minus, tol);
}
