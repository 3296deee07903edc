#include "kernels/ground/drop_study.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace clatter::kernels::ground {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kGravity_m_s2 = 9.81;

double speed_change_m_s(const BallDrop& d) { return (1 + d.restitution) * std::sqrt(2 * kGravity_m_s2 * d.drop_height_m); }

void check(const BallDrop& d) {
  if (!(d.ball_radius_m > 0 && d.ball_density_kg_m3 > 0 && d.drop_height_m > 0 && d.contact_time_s > 0 && d.distance_m > 0 &&
        d.c0_m_s > 0 && d.rho0_kg_m3 > 0 && d.restitution >= 0 && d.restitution <= 1))
    throw std::invalid_argument("drop_sound: every length, density, time and speed must be positive, restitution in [0, 1]");
  if (!(d.elevation_rad > 0 && d.elevation_rad <= kPi / 2 + 1e-12))
    throw std::invalid_argument("drop_sound: the listener must be above the ground (elevation in (0, 90] degrees)");
}

}  // namespace

double BallDrop::impulse_n_s() const {
  const double mass_kg = ball_density_kg_m3 * 4 * kPi / 3 * ball_radius_m * ball_radius_m * ball_radius_m;
  return mass_kg * speed_change_m_s(*this);
}

double DropSound::relative_db() const { return 10 * std::log10(ground_energy_pa2_s / ball_energy_pa2_s); }

double ball_pressure(const BallDrop& d, double t) {
  const double tr = t - d.distance_m / d.c0_m_s, tc = d.contact_time_s;
  if (!(tr > 0 && tr < tc)) return 0;
  // Half-sine contact force: the ball's acceleration U' = (pi dv / 2 tc) sin(pi t / tc). The compact
  // rigid sphere radiates p = (rho0 a^3 cos chi / 2) [U'/D^2 + U''/(c0 D)]; its image in the rigid
  // ground doubles it; chi is the angle from the vertical, so cos chi = sin(elevation).
  const double dv = speed_change_m_s(d), x = kPi * tr / tc;
  const double accel = kPi * dv / (2 * tc) * std::sin(x), jerk = kPi * kPi * dv / (2 * tc * tc) * std::cos(x);
  const double a3 = d.ball_radius_m * d.ball_radius_m * d.ball_radius_m;
  return d.rho0_kg_m3 * a3 * std::sin(d.elevation_rad) * (accel / (d.distance_m * d.distance_m) + jerk / (d.c0_m_s * d.distance_m));
}

DropSound drop_sound(const BallDrop& d, const model::Material& ground, double ds_per_eta, const VolumeSettings& settings) {
  check_lamb_ground(ground);
  check(d);
  DropSound out;
  // The ball: midpoint rule over the contact (its pressure is a smooth pulse of duration tc).
  const int n_ball = 4000;
  const double dt_ball = d.contact_time_s / n_ball;
  for (int i = 0; i < n_ball; ++i) {
    const double p = ball_pressure(d, d.distance_m / d.c0_m_s + (i + 0.5) * dt_ball);
    out.ball_energy_pa2_s += p * p * dt_ball;
    out.ball_peak_pa = std::max(out.ball_peak_pa, std::abs(p));
  }
  // The ground, in the bank's dimensionless form (model/ground_bank.hpp).
  const double cs = ground.shear_speed_m_s(), mach = cs / d.c0_m_s;
  const LambSurface surface(ground.poisson);
  out.eta = cs * d.contact_time_s / 4 / d.distance_m;
  // phi continues linearly past s_end (pressure_antiderivative): the window may reach 20 eta past it.
  const double eta = out.eta, s_end = std::max(mach, surface.rayleigh_tau()) + 1.5;
  const VolumeSeries phi = step_volume_series(surface, mach, d.elevation_rad, s_end, eta / ds_per_eta, settings);
  const double dt_hat = eta / 8;
  const PressureSeries pi = pressure_antiderivative(phi, eta, phi.s_start - 20 * eta, dt_hat, s_end + 20 * eta);
  const double scale = pressure_scale(ground, d.rho0_kg_m3, d.impulse_n_s(), d.distance_m);
  for (std::size_t k = 1; k < pi.pi.size(); ++k) {
    const double p = scale * (pi.pi[k] - pi.pi[k - 1]) / dt_hat;  // the average over the step
    out.ground_energy_pa2_s += p * p * dt_hat * d.distance_m / cs;
    out.ground_peak_pa = std::max(out.ground_peak_pa, std::abs(p));
  }
  return out;
}

}  // namespace clatter::kernels::ground
