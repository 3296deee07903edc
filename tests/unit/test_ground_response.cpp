// The ground's sound at a listener (kernels/ground/ground_response.hpp) against an independent
// route: the Rayleigh integral of the closed-form regularized surface acceleration
// (RegularizedLamb, kernels/ground/lamb.hpp), summed directly over the surface. The bank's route
// integrates the *unregularized* step displacement over the surface (phi) and regularizes after,
// in time: the two share only the Lamb closed forms, which tests/unit/test_lamb*.cpp check
// against the Cagniard-de Hoop quadrature. Also: the first sound overhead is a rarefaction, the
// surface's net volume vanishes for an incompressible ground, the quadrature's convergence, bad
// input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "kernels/fem/tet_quadrature.hpp"
#include "tests/unit/make_material.hpp"
#include "kernels/ground/ground_response.hpp"

using namespace clatter::kernels::ground;

namespace {

constexpr double kPi = std::numbers::pi;

struct Rule {
  std::vector<double> x, w;
};
Rule gl01(int n) {
  Rule r;
  clatter::kernels::fem::gauss_legendre_unit(n, r.x, r.w);
  return r;
}

// p(t) in the bank's units (D = 1, c_s = 1, mu = 1, rho0 = 1, unit impulse): the Rayleigh integral
// rho0 int a_n(r, t - R/c0) / (2 pi R) dA in polar coordinates about the impact point, r = r_max w^2
// (the regularized field still falls as 1/r at the impact point, which r dr cancels) and
// psi = pi u^3 (graded towards the listener's side). The field is non-causal (004's Lorentzian):
// emission from tau = -4 on is kept.
double direct_pressure(const RegularizedLamb& field, double mach, double elevation, double t, int r_panels, int psi_panels) {
  static const Rule rule = gl01(8);
  const double rho = std::cos(elevation), c0 = 1 / mach, t_from = -4;
  const double r_max = field.ground().pressure_speed_m_s() * (t - t_from) + 60 * field.epsilon_m();
  const bool overhead = rho < 1e-9;
  double sum = 0;
  for (int jp = 0; jp < (overhead ? 1 : psi_panels); ++jp)
    for (std::size_t jq = 0; jq < (overhead ? 1 : rule.x.size()); ++jq) {
      const double u0 = double(jp) / psi_panels, du = 1.0 / psi_panels, u = u0 + du * rule.x[jq];
      const double psi = overhead ? 0 : kPi * u * u * u;
      const double w_psi = overhead ? kPi : du * rule.w[jq] * 3 * kPi * u * u;
      double ray = 0;
      for (int ip = 0; ip < r_panels; ++ip)
        for (std::size_t iq = 0; iq < rule.x.size(); ++iq) {
          const double w = (ip + rule.x[iq]) / r_panels, r = r_max * w * w;
          const double big_r = std::sqrt(r * r - 2 * r * rho * std::cos(psi) + 1), tr = t - big_r / c0;
          if (tr < t_from) continue;
          ray += rule.w[iq] / r_panels * 2 * r_max * w * field.acceleration(r, tr) * r / big_r;
        }
      sum += w_psi * ray;
    }
  return sum / kPi;  // (1/2 pi) int_0^{2 pi} = (1/pi) int_0^pi
}

struct Route {
  PressureSeries pi;
  // The sample time nearest t, and dPi/dt_hat there by the central difference.
  std::size_t index(double t) const { return static_cast<std::size_t>(std::lround((t - pi.t_hat_start) / pi.dt_hat)); }
  double time(std::size_t i) const { return pi.t_hat_start + static_cast<double>(i) * pi.dt_hat; }
  double pressure(std::size_t i) const { return (pi.pi[i + 1] - pi.pi[i - 1]) / (2 * pi.dt_hat); }
};

Route bank_route(double nu, double mach, double elevation, double eta, double t_end, const VolumeSettings& set = {}) {
  const LambSurface g(nu);
  const VolumeSeries v = step_volume_series(g, mach, elevation, t_end + 2, eta / 32, set);
  return {pressure_antiderivative(v, eta, v.s_start - 10 * eta, eta / 64, t_end + 0.5)};
}

void compare_routes(double nu, double mach, double elevation_deg, double eta, int r_panels, int psi_panels, double tolerance,
                    int stride = 1) {
  const double el = elevation_deg * kPi / 180;
  const RegularizedLamb field(clatter::test::unit_ground(nu), eta);
  const LambSurface g(nu);
  const double t0 = first_arrival(g, mach, el);
  const Route bank = bank_route(nu, mach, el, eta, t0 + 1);
  double worst = 0, peak = 0;
  for (int k = -4; k <= 8; k += stride) {
    const std::size_t i = bank.index(t0 + 0.065 * k);
    const double a = bank.pressure(i), b = direct_pressure(field, mach, el, bank.time(i), r_panels, psi_panels);
    worst = std::max(worst, std::abs(a - b));
    peak = std::max(peak, std::abs(b));
  }
  std::printf("nu %.2f M %.2f elevation %.0f deg eta %.2f: bank route vs direct Rayleigh %.2e of the peak %.3e\n", nu, mach,
              elevation_deg, eta, worst / peak, peak);
  EXPECT_LT(worst / peak, tolerance);
}

}  // namespace

// Measured 3.8e-4 and 3.0e-4 overhead (the direct sum is converged: 400 and 1600 panels agree to
// 1e-7), 9.8e-4 at 30 degrees with 160 x 12 panels; the tolerances leave a factor ~3.
TEST(GroundResponse, BankRouteMatchesDirectRayleighOverhead) {
  compare_routes(0.25, 2.0, 90, 0.25, 400, 1, 1e-3);
  compare_routes(0.33, 0.5, 90, 0.25, 400, 1, 1e-3);  // a subsonic ground
}

TEST(GroundResponse, BankRouteMatchesDirectRayleighOffAxisSlow) { compare_routes(0.25, 2.0, 30, 0.25, 160, 12, 3e-3, 3); }

// The load pushes the surface away from the air: a listener overhead first hears a rarefaction.
TEST(GroundResponse, OverheadListenerHearsRarefactionFirst) {
  for (double mach : {0.5, 2.0, 9.0}) {
    const Route r = bank_route(0.25, mach, kPi / 2, 0.05, mach + 1);
    std::vector<double> p;  // pressure_scale > 0, so the sign of dPi is the pressure's
    for (std::size_t k = 1; k < r.pi.pi.size(); ++k) p.push_back(r.pi.pi[k] - r.pi.pi[k - 1]);
    double peak = 0;
    for (double v : p) peak = std::max(peak, std::abs(v));
    const auto first = std::find_if(p.begin(), p.end(), [peak](double v) { return std::abs(v) > 0.05 * peak; });
    ASSERT_NE(first, p.end());
    EXPECT_LT(*first, 0) << "M = " << mach;
  }
}

// An incompressible solid passes no volume through its surface: the step response's surface
// volume, 2 pi c_s t (P/mu) int S(tau)/tau^2 dtau, must vanish as nu -> 1/2 (it falls like alpha).
TEST(GroundResponse, SurfaceVolumeVanishesForIncompressibleGround) {
  static const Rule rule = gl01(20);
  auto volume = [](double nu) {
    const LambSurface g(nu);
    const double a = g.alpha(), xr = g.rayleigh_tau();
    double sum = g.static_value() / xr;  // S is static past the Rayleigh front
    const int panels = 400;
    for (int p = 0; p < panels; ++p)
      for (std::size_t i = 0; i < rule.x.size(); ++i) {
        const double w = (p + rule.x[i]) / panels, x = xr - (xr - a) * (1 - w) * (1 - w);  // graded at x_R
        sum += rule.w[i] / panels * 2 * (xr - a) * (1 - w) * g.step(x) / (x * x);
      }
    return sum;
  };
  const double v25 = volume(0.25), v49 = volume(0.49), v499 = volume(0.499);
  std::printf("surface volume / (2 pi c_s t P/mu): nu 0.25 %.5f, 0.49 %.5f, 0.499 %.6f\n", v25, v49, v499);
  EXPECT_GT(v25, 0);                 // net into the ground
  EXPECT_LT(v499, 0.1 * v25);        // and towards zero ...
  const double a49 = LambSurface(0.49).alpha(), a499 = LambSurface(0.499).alpha();
  EXPECT_NEAR(v499 / a499, v49 / a49, 0.03 * v49 / a49);  // ... like alpha = c_s / c_p
}

// The quadrature of phi, at the pressure: default settings against refined ones over steel
// (M = 9.1), eta = 0.05, the leaky waves before the direct sound (where rays graze the fronts) and
// the direct sound. Returns (worst difference / peak, energy difference).
std::pair<double, double> quadrature_convergence(double elevation_deg) {
  VolumeSettings fine;
  fine.nodes_per_panel = 8;
  fine.grading = 0.4;
  fine.longest_panel = 0.08;
  fine.ray_samples = 96;
  const double el = elevation_deg * kPi / 180, eta = 0.05, mach = 9.1;
  const LambSurface g(0.29);
  const double t0 = first_arrival(g, mach, el), t1 = mach + 1;
  auto series = [&](const VolumeSettings& s) {
    const VolumeSeries v = step_volume_series(g, mach, el, t1 + 1, eta / 4, s);
    return pressure_antiderivative(v, eta, t0, eta / 8, t1);
  };
  const PressureSeries a = series({}), b = series(fine);
  double worst = 0, peak = 0, energy_a = 0, energy_b = 0;
  for (std::size_t k = 1; k < a.pi.size(); ++k) {
    const double pa = a.pi[k] - a.pi[k - 1], pb = b.pi[k] - b.pi[k - 1];
    worst = std::max(worst, std::abs(pa - pb));
    peak = std::max(peak, std::abs(pb));
    energy_a += pa * pa;
    energy_b += pb * pb;
  }
  std::printf("%.0f deg, M 9.1: default vs refined quadrature: %.2e of the peak, energy %.2e\n", elevation_deg, worst / peak,
              std::abs(energy_a / energy_b - 1));
  return {worst / peak, std::abs(energy_a / energy_b - 1)};
}

TEST(GroundResponse, VolumeQuadratureConvergedSlow) {
  // Measured 1.9e-3 of the peak at the worst sample and 7e-6 in energy at 30 degrees, 9e-5 and
  // 2.1e-5 at 5 degrees (the issue asks 0.5 %). Before the grazing pairs of crossings were
  // bracketed at q's maximum, 5 degrees was off by 6 % (and by 78 % before the grazing angles
  // were graded): phi's error then jumped from sample to sample and its second derivative
  // amplified it.
  const auto [peak30, energy30] = quadrature_convergence(30);
  EXPECT_LT(peak30, 5e-3);
  EXPECT_LT(energy30, 1e-4);
  const auto [peak5, energy5] = quadrature_convergence(5);
  EXPECT_LT(peak5, 1e-3);
  EXPECT_LT(energy5, 1e-4);
}

TEST(GroundResponse, BadInput) {
  const LambSurface g(0.25);
  EXPECT_THROW(step_volume(g, 0, 1, 3), std::invalid_argument);
  EXPECT_THROW(step_volume(g, -1, 1, 3), std::invalid_argument);
  EXPECT_THROW(step_volume(g, 2, 0, 3), std::invalid_argument);   // a listener on the ground
  EXPECT_THROW(step_volume(g, 2, -0.1, 3), std::invalid_argument);  // below it
  EXPECT_THROW(step_volume(g, 2, 2.0, 3), std::invalid_argument);   // past the vertical
  EXPECT_THROW(step_volume_series(g, 2, 1, 1.0, 0.01), std::invalid_argument);  // ends before the first arrival
  const VolumeSeries v = step_volume_series(g, 2, 1, 3, 0.1);
  EXPECT_THROW(pressure_antiderivative(v, 0, 0, 0.1, 1), std::invalid_argument);
  EXPECT_THROW(pressure_antiderivative(v, 0.1, 0, 0, 1), std::invalid_argument);
  EXPECT_THROW(pressure_scale(clatter::test::unit_ground(0.25), 1.2, 1, 0), std::invalid_argument);
}
