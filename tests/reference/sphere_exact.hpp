#pragma once
// The exact pressure around a rigid sphere of radius a translating with acceleration A(t) = psi(t; h)
// along z, in linear acoustics (derivation in docs/validation.md):
//   p(r, theta, t) = -cos(theta) [F(tau) / r^2 + F'(tau) / (c r)],  tau = t - (r - a)/c,
//   F'' + 2 w F' + 2 w^2 F = -rho c^2 a A(t),  w = c / a,  F = F' = 0 before the pulse,
// solved by convolution with the impulse response k(s) = exp(-w s) sin(w s) / w.
namespace clatter::reference {

struct TranslatingSphere {
  double radius_m, c_m_s, rho_kg_m3, h_s;
  double pressure(double r_m, double cos_theta, double t_s) const;
};

// The same for any acceleration history A(t) that is smooth on each of `pieces` equal parts of
// [begin_s, end_s] and zero outside (e.g. a half-sine contact pulse).
double translating_sphere_pressure(double radius_m, double c_m_s, double rho_kg_m3, double r_m, double cos_theta,
                                   double t_s, double (*acceleration)(double t_s, const void* context),
                                   const void* context, double begin_s, double end_s, int pieces);

}  // namespace clatter::reference
