// The synthesizer's modal kernels (kernels/modal/): the proxy of 003 eq. (12), the contact point
// of Appendix F, the resonators' long-run accuracy, and the ellipsoid area of the energy rule,
// each against a reference derived here.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "kernels/modal/modal_proxy.hpp"
#include "kernels/modal/resonator_bank.hpp"
#include "kernels/rigid_body.hpp"

using namespace clatter;
using namespace clatter::kernels::modal;

TEST(ModalProxy, ContactPointHasTheNormalOppositeToTheForce) {
  // Appendix F: on x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 the outward normal is grad g / |grad g| with
  // grad g = 2 (x/a^2, y/b^2, z/c^2); it must equal n = -f/|f|, and the point lie on the surface.
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss;
  double worst_normal = 0, worst_surface = 0;
  for (const std::array<double, 3> axes : {std::array<double, 3>{0.1, 0.5, 0.86}, {0.577, 0.577, 0.578}, {0.05, 0.2, 0.978}}) {
    for (int trial = 0; trial < 2000; ++trial) {
      Vec3 n{gauss(rng), gauss(rng), gauss(rng)};
      if (trial < 6) n = {0, 0, 0}, n[static_cast<std::size_t>(trial % 3)] = trial < 3 ? 1 : -1;  // along the axes, where eq. (23) degenerates
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (double& v : n) v /= len;
      const Vec3 x = contact_point(axes, n);
      Vec3 grad{x[0] / (axes[0] * axes[0]), x[1] / (axes[1] * axes[1]), x[2] / (axes[2] * axes[2])};
      const double gl = std::sqrt(grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]);
      double g = -1;
      for (std::size_t i = 0; i < 3; ++i) {
        worst_normal = std::max(worst_normal, std::abs(grad[i] / gl - n[i]));
        g += x[i] * x[i] / (axes[i] * axes[i]);
      }
      worst_surface = std::max(worst_surface, std::abs(g));
    }
  }
  std::printf("Appendix F: worst |normal - n| %.3g, worst |g(x)| %.3g over 6000 directions\n", worst_normal, worst_surface);
  EXPECT_LE(worst_normal, 1e-12);
  EXPECT_LE(worst_surface, 1e-12);
}

TEST(ModalProxy, Equation12GivesTheEllipsoidsOwnAxesAndAProperRotation) {
  // A solid ellipsoid with semi-axes (3, 1, 2) (body x, y, z), turned: eq. (12) must return its
  // normalized axes in ascending order, and R must map each body axis onto the proxy axis of the
  // same length (up to sign), with det R = +1.
  const double a = 3, b = 1, c = 2, m = 5, pi = std::numbers::pi;
  const double s = 0.6, co = 0.8;  // a rotation about z by atan(3/4)
  const kernels::Mat3 q{{{co, -s, 0}, {s, co, 0}, {0, 0, 1}}};
  const Vec3 diag{m / 5 * (b * b + c * c), m / 5 * (a * a + c * c), m / 5 * (a * a + b * b)};
  kernels::Mat3 inertia{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t k = 0; k < 3; ++k) inertia[i][j] += q[i][k] * diag[k] * q[j][k];
  const auto fit = kernels::fit_proxy(inertia, m, 4.0 / 3.0 * pi * a * b * c);
  const ModalProxyFrame f = modal_proxy_frame(fit);
  const double norm = std::sqrt(a * a + b * b + c * c);
  EXPECT_NEAR(f.unit_axes[0], b / norm, 1e-12);
  EXPECT_NEAR(f.unit_axes[1], c / norm, 1e-12);
  EXPECT_NEAR(f.unit_axes[2], a / norm, 1e-12);
  const auto& r = f.rotation;
  const double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                     r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
  EXPECT_NEAR(det, 1.0, 1e-12);
  // The body's y axis (length b, the shortest) turned by q is the proxy's x axis.
  const Vec3 body_y{q[0][1], q[1][1], q[2][1]}, body_x{q[0][0], q[1][0], q[2][0]};
  EXPECT_NEAR(std::abs(to_modal_frame(f, body_y)[0]), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(to_modal_frame(f, body_x)[2]), 1.0, 1e-12);
}

TEST(ResonatorBank, FiveSecondsOfRingingStayOnTheExactSinusoid) {
  // The two-pole recursion carries Im(C e^{s t}) exactly in exact arithmetic. In doubles the
  // rounding of a1 = 2 cos(w dt) (at most eps) moves the frequency by eps / (2 sin(w dt) dt), so
  // after N steps the phase has drifted by at most N eps / (2 sin(w dt)): 8.5e-9 rad at 20 Hz over
  // 5 s, where a1 -> 2 makes the recursion least well conditioned. The reference itself loses
  // eps w t to the rounding of its argument (1e-10 at 15 kHz). The error must stay within twice
  // the sum, undamped, over a whole scene.
  for (const double f_hz : {20.0, 440.0, 15000.0}) {
    const double rate = 44100, omega = 2 * std::numbers::pi * f_hz;
    const std::complex<double> pole{-0.0, omega}, c{0.3, -1.1};
    ResonatorBank bank(rate);
    std::vector<double> out(static_cast<std::size_t>(5 * rate), 0.0);
    bank.inject(bank.add(pole), 10, c, 0.0);
    bank.render(0, out);
    double worst = 0;
    for (std::size_t n = 10; n < out.size(); ++n) worst = std::max(worst, std::abs(out[n] - (c * std::exp(pole * (static_cast<double>(n) / rate))).imag()));
    const double steps = static_cast<double>(out.size()), drift = steps * 2.2e-16 * (1 / (2 * std::sin(omega / rate)) + omega / rate);
    std::printf("resonator at %g Hz: worst error over 5 s %.3g of the amplitude (phase-drift bound %.3g)\n", f_hz,
                worst / std::abs(c), drift);
    EXPECT_LT(worst, 2 * drift * std::abs(c));
    for (std::size_t n = 0; n < 10; ++n) EXPECT_EQ(out[n], 0.0);
  }
}

// The ellipsoid's area (kernels/rigid_body.hpp, for the energy rule of the modal source) against
// the closed forms of the sphere and the spheroids, the flat limit 2 pi a b, and Thomsen's
// approximation (within 1.1 %) for a general ellipsoid in every order of its axes.
TEST(EllipsoidArea, ClosedFormsOfTheSphereAndSpheroidsAndTheFlatLimit) {
  using clatter::kernels::ellipsoid_surface_area_m2;
  const double pi = std::numbers::pi;
  EXPECT_NEAR(ellipsoid_surface_area_m2(0.3, 0.3, 0.3), 4 * pi * 0.09, 1e-14);
  {  // oblate, a = b = 2, c = 1: 2 pi a^2 (1 + (1 - e^2) atanh(e) / e)
    const double e = std::sqrt(1 - 0.25), expected = 2 * pi * 4 * (1 + (1 - e * e) * std::atanh(e) / e);
    EXPECT_NEAR(ellipsoid_surface_area_m2(2, 2, 1), expected, 1e-12 * expected);
    EXPECT_NEAR(ellipsoid_surface_area_m2(1, 2, 2), expected, 1e-12 * expected);
  }
  {  // prolate, a = 2, b = c = 1: 2 pi b^2 (1 + a asin(e) / (b e))
    const double e = std::sqrt(1 - 0.25), expected = 2 * pi * (1 + 2 * std::asin(e) / e);
    EXPECT_NEAR(ellipsoid_surface_area_m2(2, 1, 1), expected, 1e-12 * expected);
  }
  EXPECT_NEAR(ellipsoid_surface_area_m2(1, 0.8, 1e-4), 2 * pi * 0.8, 1e-3 * 2 * pi * 0.8);  // both faces of the disc
  const double p = 1.6075, thomsen = 4 * pi * std::pow((std::pow(6.0, p) + std::pow(3.0, p) + std::pow(2.0, p)) / 3, 1 / p);
  for (const auto& r : {std::array<double, 3>{3, 2, 1}, {1, 3, 2}, {2, 1, 3}}) {
    const double area = ellipsoid_surface_area_m2(r[0], r[1], r[2]);
    EXPECT_NEAR(area, thomsen, 0.011 * thomsen);
    EXPECT_NEAR(area, ellipsoid_surface_area_m2(3, 2, 1), 1e-13 * area);
  }
}
