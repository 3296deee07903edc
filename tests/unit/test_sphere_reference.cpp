// The exact translating-sphere solution (tests/reference) checked against the equations it must
// satisfy, independently of how it is evaluated.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/pulse.hpp"
#include "tests/reference/ellipsoid_added_mass.hpp"
#include "tests/reference/sphere_exact.hpp"

using clatter::reference::TranslatingSphere;

namespace {
const TranslatingSphere kSphere{0.1, 343.2, 1.2041, 1e-4};
}

TEST(SphereReference, SatisfiesTheRigidBoundaryCondition) {
  // dp/dr at r = a equals -rho A(t) cos(theta) (eq. 9 for a translation along z).
  const double a = kSphere.radius_m, d = 1e-7;
  for (double t : {-1.5e-4, -0.5e-4, 0.0, 0.7e-4, 1.6e-4, 3e-4}) {
    const double dpdr = (kSphere.pressure(a + d, 0.6, t) - kSphere.pressure(a - d, 0.6, t)) / (2 * d);
    const double want = -kSphere.rho_kg_m3 * clatter::kernels::pulse(t, kSphere.h_s) * 0.6;
    EXPECT_NEAR(dpdr, want, 1e-5 * kSphere.rho_kg_m3) << "t = " << t;
  }
}

TEST(SphereReference, SolvesTheWaveEquationForADipole) {
  // p = f(r, t) cos(theta): f_tt = c^2 (f_rr + 2 f_r / r - 2 f / r^2).
  const double c = kSphere.c_m_s, r = 0.23, t = (r - kSphere.radius_m) / c + 0.4e-4;
  const double dt = 2e-7, dr = c * dt;
  auto f = [&](double rr, double tt) { return kSphere.pressure(rr, 1.0, tt); };
  const double f_tt = (f(r, t + dt) - 2 * f(r, t) + f(r, t - dt)) / (dt * dt);
  const double f_r = (f(r + dr, t) - f(r - dr, t)) / (2 * dr);
  const double f_rr = (f(r + dr, t) - 2 * f(r, t) + f(r - dr, t)) / (dr * dr);
  EXPECT_NEAR(f_tt, c * c * (f_rr + 2 * f_r / r - 2 * f(r, t) / (r * r)), 2e-3 * std::abs(f_tt));
}

TEST(SphereReference, SlowPulseGivesTheIncompressibleAddedMassPressure) {
  // For a pulse much longer than a/c the surface pressure is rho a A(t) cos(theta) / 2.
  const TranslatingSphere slow{0.1, 343.2, 1.2041, 100 * 0.1 / 343.2};
  for (double s : {-1.0, 0.0, 0.5}) {
    const double t = s * slow.h_s;
    const double want = slow.rho_kg_m3 * slow.radius_m * clatter::kernels::pulse(t, slow.h_s) / 2;
    EXPECT_NEAR(slow.pressure(slow.radius_m, 1.0, t), want, 0.02 * slow.rho_kg_m3 * slow.radius_m / 2) << s;
  }
}

TEST(SphereReference, NothingBeforeTheWaveArrives) {
  const double r = 0.5, arrival = (r - kSphere.radius_m) / kSphere.c_m_s - 2 * kSphere.h_s;
  EXPECT_EQ(kSphere.pressure(r, 1.0, arrival - 1e-6), 0.0);
}

// Lamb's translation dipole M = 2V / (2 - alpha) in its closed-form limits: a sphere carries half
// its volume as added mass (M = 3V/2) along any axis; a circular disc of radius R broadside,
// c -> 0, the added mass 8 rho R^3 / 3 and no volume; edgewise nothing but its vanishing volume.
TEST(EllipsoidAddedMass, SphereAndDiscLimits) {
  using clatter::reference::ellipsoid_translation_dipole_m3;
  const double pi = 3.14159265358979323846, r = 0.3;
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_NEAR(ellipsoid_translation_dipole_m3(r, r, r, axis), 1.5 * 4.0 / 3.0 * pi * r * r * r, 1e-12);
  const double thin = 1e-6;
  EXPECT_NEAR(ellipsoid_translation_dipole_m3(r, r, thin, 2) / (8.0 / 3.0 * r * r * r), 1.0, 1e-5);
  EXPECT_LT(ellipsoid_translation_dipole_m3(r, r, thin, 0), 1e-3 * r * r * r);
  // The order of the semi-axes does not matter, only which one the motion is along.
  EXPECT_NEAR(ellipsoid_translation_dipole_m3(0.5, 0.12, 0.025, 2), ellipsoid_translation_dipole_m3(0.025, 0.5, 0.12, 0), 1e-15);
}
