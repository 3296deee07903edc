#pragma once
// Free vibration of a homogeneous, isotropic, traction-free elastic sphere (Lamb 1882): the
// characteristic equations and their roots, an independent reference for the FEM modal analysis
// (derivation and tables in docs/validation.md, "Free vibration of an elastic sphere (Lamb)").
// With x = omega a / c_p and y = omega a / c_s (a the radius), a mode of degree n is
//   torsional (class I, n >= 1):   (n - 1) j_n(y) - y j_{n+1}(y) = 0,
//   spheroidal (class II, n >= 0): det [[a11, a12], [a21, a22]] = 0 (the radial and shear
//   tractions of the P and S potentials; n = 0 keeps a11 alone),
// and has multiplicity 2n + 1 (the orders m = -n..n share it).
#include <vector>

namespace clatter::reference {

enum class LambFamily { torsional, spheroidal };

struct LambMode {
  LambFamily family;
  int degree_n;
  int overtone;      // 0 for the lowest root of (family, n) above zero frequency
  int multiplicity;  // 2n + 1
  double omega_a_over_cs;
};

// The characteristic functions, entire in y (no poles), for Poisson ratio nu in [0, 1/2).
// spheroidal_determinant: from the potentials, derived in docs/validation.md.
// spheroidal_saviot: the published ratio form (Saviot et al. 2004 after Eringen & Suhubi 1975),
// multiplied through by j_n(x) j_n(y); n >= 1 only. Their roots must coincide.
double lamb_torsional(int n, double y);
double lamb_spheroidal_determinant(int n, double y, double poisson_ratio);
double lamb_spheroidal_saviot(int n, double y, double poisson_ratio);

// Every mode with 0 < omega a / c_s <= max_omega_a_over_cs, sorted by frequency; roots bracketed
// on a grid of step scan_step in y, then bisected to 1e-14 relative.
std::vector<LambMode> lamb_sphere_modes(double poisson_ratio, double max_omega_a_over_cs, double scan_step = 5e-3);

// The same roots of one characteristic function, for the tests: f(n, y) on (y_min, y_max].
std::vector<double> lamb_roots(double (*f)(int n, double y, double poisson_ratio), int n, double poisson_ratio,
                               double y_min, double y_max, double scan_step);

// The frequency in Hz of a mode for a sphere of the given radius and material.
double lamb_frequency_hz(const LambMode& mode, double radius_m, double youngs_modulus_pa, double poisson_ratio,
                         double rho_kg_m3);

// c_p / c_s = sqrt(2 (1 - nu) / (1 - 2 nu)).
double lamb_speed_ratio(double poisson_ratio);

}  // namespace clatter::reference
