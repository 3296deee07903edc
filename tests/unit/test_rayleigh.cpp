// The Rayleigh integral of the ground's radiation (kernels/ground/rayleigh.hpp) against fields
// with closed forms, each driven by a smooth velocity pulse: the rigid baffled piston on its axis,
// the whole plane moving as one (a plane wave at any horizontal offset), and a small piston far
// off its axis (the baffled monopole); and the convergence of the quadrature with its resolution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "kernels/ground/rayleigh.hpp"

using namespace clatter::kernels::ground;

namespace {

constexpr double kPi = std::numbers::pi;

// v(t) = exp(-((t - t0)/w)^2) with t0 = 5 w (v(0) = 1e-11), and v'.
struct Pulse {
  double w_s, t0_s;
  double v(double t) const {
    const double x = (t - t0_s) / w_s;
    return std::exp(-x * x);
  }
  double dv(double t) const {
    const double x = (t - t0_s) / w_s;
    return -2 * x / w_s * std::exp(-x * x);
  }
};

SurfaceField piston(const Pulse& p, double radius_m) {
  return {[p, radius_m](double r, double tau) { return r <= radius_m ? p.dv(tau) : 0.0; },
          [radius_m](double) { return radius_m; }};
}

// Worst |p - exact| over times t0 .. t0 + span, relative to the exact peak.
template <class Exact>
double worst_error(const SurfaceField& f, double rho, double z, double t0, double span, const RayleighSettings& s, Exact exact,
                   long* evaluations = nullptr) {
  double worst = 0, peak = 0;
  for (int k = 0; k <= 40; ++k) {
    const double t = t0 + span * k / 40;
    const RayleighPressure p = rayleigh_pressure(f, rho, z, t, s);
    if (evaluations) *evaluations += p.evaluations;
    worst = std::max(worst, std::abs(p.pressure_pa - exact(t)));
    peak = std::max(peak, std::abs(exact(t)));
  }
  return worst / peak;
}

}  // namespace

TEST(Rayleigh, BaffledPistonOnItsAxis) {
  // p(z, t) = rho_0 c [v(t - z/c) - v(t - sqrt(z^2 + a^2)/c)]: the direct wave from the piston's
  // face and the edge wave (Kinsler et al., Fundamentals of Acoustics, 7.4, transient form).
  const Pulse pulse{2e-4, 1e-3};
  const double radius = 0.1;
  const RayleighSettings s;
  for (const double z : {0.05, 0.3, 1.0}) {
    const double err = worst_error(piston(pulse, radius), 0, z, z / s.c0_m_s, 3e-3, s, [&](double t) {
      return s.rho0_kg_m3 * s.c0_m_s * (pulse.v(t - z / s.c0_m_s) - pulse.v(t - std::hypot(z, radius) / s.c0_m_s));
    });
    std::printf("Rayleigh: piston a = 0.1 m on its axis at z = %g m: worst error %.3g of the peak\n", z, err);
    EXPECT_LT(err, 1e-8);
  }
}

TEST(Rayleigh, TheWholePlaneMovingAsOneRadiatesAPlaneWaveEverywhere) {
  // a(r, tau) = v'(tau) everywhere (support infinite): p = rho_0 c v(t - z/c) at any offset, which
  // exercises the off-axis rings and the end of R at c_0 t.
  const Pulse pulse{2e-4, 1e-3};
  const SurfaceField plane{[&](double, double tau) { return pulse.dv(tau); },
                           [](double) { return std::numeric_limits<double>::infinity(); }};
  RayleighSettings s;
  s.resolution_m = 0.02;  // the pulse is 7 cm long in R; psi sees a constant
  for (const double rho : {0.0, 0.7, 3.0}) {
    const double z = 0.4;
    const double err = worst_error(plane, rho, z, z / s.c0_m_s, 3e-3, s, [&](double t) {
      return s.rho0_kg_m3 * s.c0_m_s * pulse.v(t - z / s.c0_m_s);
    });
    std::printf("Rayleigh: the plane moving as one, rho = %g m: worst error %.3g of rho_0 c v_max\n", rho, err);
    EXPECT_LT(err, 1e-8);
  }
}

TEST(Rayleigh, ASmallPistonFarOffItsAxisConvergesToTheBaffledMonopole) {
  // A 1 cm piston 1.5 m off axis at 1.5 m height (45 degrees, R = 2.12 m), pulse 1 ms (k a = 0.06 at
  // its centre frequency): p = rho_0 A v'(t - R/c) / (2 pi R) times the piston's directivity and
  // the near-field terms, which differ from 1 by (k a sin th)^2 / 8 and a / R: below 0.1 %. The
  // resolution is halved until the result stops changing: the convergence study of the quadrature.
  const Pulse pulse{1e-3, 5e-3};
  const double radius = 0.01, rho = 1.5, z = 1.5, big_r = std::hypot(rho, z), area = kPi * radius * radius;
  RayleighSettings s;
  double previous = 0;
  for (const double h : {4e-3, 2e-3, 1e-3}) {
    s.resolution_m = h;
    long evaluations = 0;
    const double err = worst_error(piston(pulse, radius), rho, z, big_r / s.c0_m_s, 1e-2, s, [&](double t) {
      return s.rho0_kg_m3 * area * pulse.dv(t - big_r / s.c0_m_s) / (2 * kPi * big_r);
    }, &evaluations);
    std::printf("Rayleigh: 1 cm piston, 45 deg off axis, resolution %g m: deviation from the monopole %.3g of the peak "
                "(%ld field evaluations per sample)\n", h, err, evaluations / 41);
    if (h < 4e-3) {
      EXPECT_LT(std::abs(err - previous), 5e-3);  // converged to 0.5 % between halvings
    }
    previous = err;
  }
  EXPECT_LT(previous, 2e-3);
}

TEST(Rayleigh, RefusesAListenerOnOrBelowTheSurface) {
  const SurfaceField f = piston({1e-3, 5e-3}, 0.1);
  EXPECT_THROW(rayleigh_pressure(f, 1, 0, 0.01), std::invalid_argument);
  EXPECT_THROW(rayleigh_pressure(f, 1, -0.5, 0.01), std::invalid_argument);
  EXPECT_THROW(rayleigh_pressure(f, -1, 0.5, 0.01), std::invalid_argument);
  EXPECT_EQ(rayleigh_pressure(f, 0, 1, 1e-3).pressure_pa, 0.0);  // before the first sound arrives
}
