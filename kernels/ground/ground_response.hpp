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

struct VolumeSeries {
  double s_start = 0, ds = 0;  // phi at s_start + k ds; s_start is first_arrival()
  std::vector<double> phi;
};
VolumeSeries step_volume_series(const LambSurface& ground, double mach, double elevation_rad, double s_end, double ds,
                                const VolumeSettings& settings = {});

// Pi(t_hat) = -d^2/dt_hat^2 (f_eta * phi)(t_hat) on t_hat_start + k dt_hat up to t_hat_end, with phi
// taken as linear between its samples (so f_eta * phi'' is a sum of smoothed deltas, one per
// sample, weighted by the jump in phi's slope) and continued linearly past its last sample. Needs
// ds well below eta (eta / 8 keeps the interpolation error under 1e-4: docs/ground.md).
struct PressureSeries {
  double t_hat_start = 0, dt_hat = 0;
  std::vector<double> pi;
};
PressureSeries pressure_antiderivative(const VolumeSeries& volume, double eta, double t_hat_start, double dt_hat, double t_hat_end);

// p(t) = pressure_scale * dPi/dt_hat at t_hat = c_s t / D, for an impulse J [N s] and the air's
// density rho0; the sign makes p a pressure (compression positive) for a load into the ground.
double pressure_scale(const model::Material& ground, double rho0_kg_m3, double impulse_n_s, double distance_m);

}  // namespace clatter::kernels::ground
