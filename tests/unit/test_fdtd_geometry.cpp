// Cut-cell geometry against closed-form volumes and surface integrals of the ellipsoid.
#include <gtest/gtest.h>

#include <cmath>

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
