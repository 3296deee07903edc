#pragma once
// Free vibration of a free-free slender bar of rectangular section, an independent reference for
// modal models of closed meshes (clatter-bank object):
//   bending by Timoshenko's beam theory (shear deformation and rotary inertia), shear coefficient
//   of a rectangle by Cowper (1966), k = 10 (1 + nu) / (12 + 11 nu); the free-free frequency
//   equation solved numerically (a 4 x 4 determinant of the free-end conditions, bracketed on a
//   grid and bisected);
//   torsion by Saint-Venant's theory (no warping inertia or restraint): f_m = (m / 2L)
//   sqrt(G J / (rho I_p)), J of a rectangle from its series, I_p = b h (b^2 + h^2) / 12.
// Derivations and the checks against Euler-Bernoulli and Roark: tests/unit/test_bar_plate_modes.cpp.

namespace clatter::reference {

struct Bar {
  double length_m = 0;
  double width_m = 0, depth_m = 0;  // bending across depth_m (I = width depth^3 / 12): the lower
                                    // family when depth_m < width_m
  double youngs_pa = 0, poisson = 0, rho_kg_m3 = 0;
};

// Cowper's shear coefficient of a rectangular section.
double cowper_shear_coefficient_rectangle(double poisson);

// The m-th root (m >= 1) of cos x cosh x = 1 above 0: beta_m L of a free-free Euler-Bernoulli beam
// (4.730040744862704 for m = 1).
double free_free_beta_l(int mode);
// f_m = (beta_m L)^2 / (2 pi L^2) sqrt(E I / (rho A)).
double euler_bernoulli_free_free_bending_hz(const Bar& bar, int mode = 1);
// The m-th free-free bending frequency of the Timoshenko beam (modes below the second spectrum's
// cutoff sqrt(k G A / (rho I)), every mode of a slender bar); std::runtime_error otherwise.
double timoshenko_free_free_bending_hz(const Bar& bar, int mode = 1);
// The free-free Timoshenko determinant at angular frequency omega (its roots are the frequencies;
// exposed for the tests).
double timoshenko_free_free_determinant(const Bar& bar, double omega_rad_s);

// Saint-Venant's torsion constant of a long_m x short_m rectangle (either order):
// J = a b^3 [1/3 - (64 / pi^5) (b / a) sum_{n odd} tanh(n pi a / 2b) / n^5], a >= b, summed until
// the terms fall below 1e-17 of the sum.
double rectangle_torsion_constant_m4(double side_a_m, double side_b_m);
// The m-th free-free torsion frequency (m >= 1).
double saint_venant_free_free_torsion_hz(const Bar& bar, int mode = 1);

}  // namespace clatter::reference
