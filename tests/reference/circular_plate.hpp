#pragma once
// Free flexural vibration of a thin circular plate with a free edge by Kirchhoff's theory (no
// shear deformation or rotary inertia), the exact frequency equation as in Leissa, Vibration of
// Plates (NASA SP-160, 1969), chapter 2 (solid circular plates, free edge): with W = [A J_n(k r) +
// C I_n(k r)] cos(n theta), k^4 = rho t omega^2 / D, D = E t^3 / (12 (1 - nu^2)), lambda = k R,
// zero radial moment and zero Kirchhoff shear at r = R give
//   [l^2 J_n + (1-nu)(l J_n' - n^2 J_n)] [l^3 I_n' - (1-nu) n^2 (l I_n' - I_n)]
// - [l^2 I_n - (1-nu)(l I_n' - n^2 I_n)] [l^3 J_n' + (1-nu) n^2 (l J_n' - J_n)] = 0   (l = lambda),
// an entire function of lambda (no poles), whose roots give omega R^2 sqrt(rho t / D) = lambda^2.
// Derived from M_r = 0 and V_r = Q_r + (1/r) dM_rt/dtheta = 0 with Bessel's equations for J_n and
// I_n; checked against Leissa's tabulated values in tests/unit/test_bar_plate_modes.cpp.
#include <vector>

namespace clatter::reference {

struct PlateMode {
  int diameters_n;  // nodal diameters (n >= 1: a degenerate pair, cos and sin n theta)
  int circles_s;    // nodal circles (n = 0 and 1 start at s = 1: s = 0 there is a rigid motion)
  double lambda2;   // omega R^2 sqrt(rho t / D)
};

// The frequency equation's left side above.
double free_circular_plate_equation(int n, double lambda, double poisson);

// The `count` lowest distinct flexural modes (a pair with n >= 1 counted once), rigid motions left
// out, sorted by frequency; roots bracketed on a grid of 1e-3 in lambda and bisected to 1e-15.
std::vector<PlateMode> free_circular_plate_modes(double poisson, int count);

// f = lambda^2 / (2 pi R^2) sqrt(D / (rho t)).
double circular_plate_frequency_hz(const PlateMode& mode, double radius_m, double thickness_m, double youngs_pa,
                                   double poisson, double rho_kg_m3);

// A first-order estimate of Mindlin's frequency over Kirchhoff's for a mode of wavenumber
// k = lambda / R: a straight-crested flexural wave in a Mindlin plate (shear coefficient
// kappa^2 = pi^2 / 12) at that wavenumber, omega_M / omega_K = 1 - (k t)^2 / 24 (1 + 2 / (kappa^2
// (1 - nu))), the rotary inertia (the 1) and the shear (the rest). It ignores the edge.
double mindlin_over_kirchhoff_estimate(double lambda2, double thickness_over_radius, double poisson);

}  // namespace clatter::reference
