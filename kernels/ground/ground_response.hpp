#pragma once
// The sound of the ground at a listener, in the dimensionless form the ground bank stores
// (model/ground_bank.hpp gives the scaling; docs/ground.md the derivation and the error study).
//
// Units: the listener is at distance 1 and elevation theta from the impact point, c_s = 1, mu = 1,
// a unit load, the air's sound speed 1/M (M = c_s / c0). Then
//   phi(s) = (1/2 pi) int_0^{2 pi} dpsi int_0^inf dr  S(q(r, psi); nu) / R(r, psi),
//   q = (s - M R) / r,   R^2 = r^2 - 2 r cos(theta) cos(psi) + 1,
// is the Rayleigh integral of the step displacement (S from kernels/ground/lamb.hpp) at time s:
// polar coordinates about the impact point, so the 1/r of the static field cancels against dA,
// and on each ray the fronts (q = alpha, 1, x_R) are found and made panel edges, with a
// square-root graded rule at the Rayleigh front's 1/sqrt singularity, and panels graded towards
// the point under the listener (the kernel's 1/R peaks there, at height sin(theta)). Before the
// direct sound (s < M: a ground wave faster than the air, heard at a low elevation) a ray may graze
// a front: the angles where it does become psi panel edges, graded geometrically (the ray integral
// has a logarithmic singularity there), and a grazing ray is graded towards q's maximum.
#include <vector>

#include "kernels/ground/lamb.hpp"
#include "model/ground_bank.hpp"

namespace clatter::kernels::ground {

struct VolumeSettings {
  // Measured against 12 points, grading 0.3, 0.05-long panels and 200 ray samples at 5 and 30
  // degrees over steel (M = 9.1): 1e-5 of phi's peak (docs/ground.md).
  int nodes_per_panel = 6;      // Gauss-Legendre points per panel, in r and in psi
  double grading = 0.7;         // a panel is at most this fraction of its distance to the listener's foot ...
  double finest_panel = 0.25;   // ... and at least this fraction of the listener's height sin(theta)
  double longest_panel = 0.15;  // in r (units of D) and in psi (radians)
  int ray_samples = 64;         // samples of q along a ray that bracket its fronts
};

// The earliest time s at which anything reaches the listener: the direct sound M, or earlier for a
// P wave faster than the air at a low elevation (its leaky wave leaves the surface at the critical
// angle). phi(s) = 0 before it.
double first_arrival(const LambSurface& ground, double mach, double elevation_rad);

// phi(s) as above. std::invalid_argument for mach <= 0 or an elevation outside (0, pi/2].
double step_volume(const LambSurface& ground, double mach, double elevation_rad, double s, const VolumeSettings& settings = {});

// phi past the end of its series (docs/ground.md "The end of a series and the tail"). Once the
// Rayleigh wave has passed, the static field fills a disk growing with s, and its 1/r displacement
// makes phi grow as C ln s, C = (1 - nu) / (2 pi) exactly (Boussinesq); what is left decays as
// powers of 1/s. So phi(s) = C ln s + sum_j g[j] (s_join / s)^j, fitted to phi's last sample, the
// slope of its last segment and step_volume at seven points out to 16 s_join. Its Pi is the
// closed form
//   Pi(t_hat) = -(f_eta * phi'')(t_hat) = sum_m pi_tail[m - 2] R_m(t_hat),
//   R_m = 2 Re (t_hat + i eta)^-m - Re (t_hat + 2 i eta)^-m,   m = 2 .. kTailTerms + 1
// (the Lorentzian is the Poisson kernel, so P_eta * s^-m = Re (s + i eta)^-m), which is what a
// bank stores per series and a synthesizer continues the series with.
inline constexpr int kTailTerms = static_cast<int>(model::kGroundTailTerms);
struct VolumeTail {
  double s_join = 0;       // the series' last sample, where the tail takes over
  double log_coefficient = 0;  // C
  std::vector<double> g;   // g[0] .. g[kTailTerms - 1]
  double phi(double s) const;
  // The Pi coefficients above: pi_tail[0] = C, pi_tail[j + 1] = -g[j] s_join^j j (j + 1).
  std::vector<double> pi_tail() const;
};
// sum_m coefficients[m - 2] R_m(t_hat; eta); 0 for no coefficients.
double tail_antiderivative(const std::vector<double>& coefficients, double t_hat, double eta);

struct VolumeSeries {
  double s_start = 0, ds = 0;  // phi at s_start + k ds; s_start is first_arrival()
  std::vector<double> phi;
  VolumeTail tail;             // phi past the last sample
};
// The samples and their tail (phi continued past s_end as above).
VolumeSeries step_volume_series(const LambSurface& ground, double mach, double elevation_rad, double s_end, double ds,
                                const VolumeSettings& settings = {});

// Pi(t_hat) = -d^2/dt_hat^2 (f_eta * phi)(t_hat) on t_hat_start + k dt_hat up to t_hat_end, with phi
// taken as linear between its samples (so f_eta * phi'' is a sum of smoothed deltas, one per
// sample, weighted by the jump in phi's slope) and continued past its last sample by its tail,
// sampled on the same step. The error of the linear phi is second order in ds / eta, largest where
// leaky waves make phi least smooth: on the rendered pressure (concrete, eta 0.02), 0.017 % overhead
// between ds = eta / 8 and eta / 16, but 1.84 % at 30 degrees at eta / 8 and 0.27 % at eta / 16
// (docs/ground.md).
struct PressureSeries {
  double t_hat_start = 0, dt_hat = 0;
  std::vector<double> pi;
};
PressureSeries pressure_antiderivative(const VolumeSeries& volume, double eta, double t_hat_start, double dt_hat, double t_hat_end);

// p(t) = pressure_scale * dPi/dt_hat at t_hat = c_s t / D, for an impulse J [N s] and the air's
// density rho0; the sign makes p a pressure (compression positive) for a load into the ground.
double pressure_scale(const model::Material& ground, double rho0_kg_m3, double impulse_n_s, double distance_m);

}  // namespace clatter::kernels::ground
