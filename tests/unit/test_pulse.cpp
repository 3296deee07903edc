// psi(t; h) against the properties the PAN method relies on (Chadwick et al. 2012, eqs. 5-6), and
// the monopole field against the spherical wave equation it must solve.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/pulse.hpp"

using clatter::kernels::monopole_pressure;
using clatter::kernels::pulse;

namespace {
constexpr double kH = 1e-4;
}

TEST(Pulse, PartitionOfUnity) {
  // Eq. (5) reproduces a constant acceleration exactly only if sum_k psi(t - kh) = 1 for all t.
  for (int i = 0; i <= 1000; ++i) {
    const double t = kH * (-3.0 + 6.0 * i / 1000.0);
    double sum = 0;
    for (int k = -6; k <= 6; ++k) sum += pulse(t - k * kH, kH);
    EXPECT_NEAR(sum, 1.0, 1e-14) << "t = " << t;
  }
}

TEST(Pulse, SupportSymmetryAndKnots) {
  EXPECT_DOUBLE_EQ(pulse(0.0, kH), 7.0 / 9.0);
  EXPECT_DOUBLE_EQ(pulse(kH, kH), 1.0 / 9.0);
  EXPECT_DOUBLE_EQ(pulse(-kH, kH), 1.0 / 9.0);
  EXPECT_EQ(pulse(2 * kH, kH), 0.0);
  EXPECT_EQ(pulse(2.5 * kH, kH), 0.0);
  EXPECT_EQ(pulse(-7 * kH, kH), 0.0);
  for (double a : {0.1, 0.7, 1.3, 1.9}) EXPECT_EQ(pulse(a * kH, kH), pulse(-a * kH, kH));
}

TEST(Pulse, IntegratesToH) {
  // Composite Simpson over the support; psi is a piecewise cubic with knots on the grid, so exact.
  const int n = 4000;
  const double a = -2 * kH, step = 4 * kH / n;
  double s = pulse(a, kH) + pulse(a + n * step, kH);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * pulse(a + i * step, kH);
  EXPECT_NEAR(s * step / 3.0, kH, 1e-12 * kH);
}

TEST(Pulse, ContinuousFirstDerivativeAtKnots) {
  // One-sided difference quotients agree at |t| = h and |t| = 2h (C1), and vanish at t = 0.
  const double d = 1e-7 * kH;
  for (double knot : {0.0, kH, 2 * kH}) {
    const double left = (pulse(knot, kH) - pulse(knot - d, kH)) / d;
    const double right = (pulse(knot + d, kH) - pulse(knot, kH)) / d;
    EXPECT_NEAR(left, right, 1e-5 / kH) << "knot " << knot;
  }
  EXPECT_NEAR((pulse(kH + d, kH) - pulse(kH - d, kH)) / (2 * d), -0.5 / kH, 1e-5 / kH);  // psi'(h) = -1/(2h)
}

TEST(Pulse, ScaleInvariance) {
  // psi(beta t; beta h) = psi(t; h): the identity behind the scaling law, eq. (10).
  for (double beta : {0.25, 3.0})
    for (double t : {-1.7e-4, -0.3e-4, 0.0, 0.9e-4, 1.5e-4})
      EXPECT_NEAR(pulse(beta * t, beta * kH), pulse(t, kH), 1e-15);
}

TEST(Monopole, SolvesSphericalWaveEquation) {
  // u = r p satisfies u_tt = c^2 u_rr; check with centred second differences away from the knots.
  const double c = 343.2, rho = 1.2041, r = 0.3, t = r / c + 0.37 * kH;
  const double dt = 1e-3 * kH, dr = c * dt;
  auto u = [&](double rr, double tt) { return rr * monopole_pressure(rr, tt, kH, c, rho); };
  const double u_tt = (u(r, t + dt) - 2 * u(r, t) + u(r, t - dt)) / (dt * dt);
  const double u_rr = (u(r + dr, t) - 2 * u(r, t) + u(r - dr, t)) / (dr * dr);
  EXPECT_NEAR(u_tt, c * c * u_rr, 1e-4 * std::abs(u_tt));
  EXPECT_GT(std::abs(u_tt), 0.0);
}

TEST(Monopole, SphericalSpreadingAndAmplitude) {
  // Along a characteristic t = r/c + tau, r p is constant and equals rho psi(tau) / (4 pi).
  const double c = 343.2, rho = 1.2041, tau = 0.4 * kH;
  for (double r : {0.05, 0.5, 5.0})
    EXPECT_NEAR(r * monopole_pressure(r, r / c + tau, kH, c, rho), rho * pulse(tau, kH) / (4 * M_PI), 1e-14);
}
