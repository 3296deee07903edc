#pragma once
// Lamb's problem: the vertical displacement of the surface of an elastic half-space under a
// vertical point load suddenly applied at its surface (docs/ground.md derives every formula).
//
// Sign conventions, used everywhere in kernels/ground: the load P pushes into the ground; the
// displacement u is positive in the load's direction (into the ground); the surface's normal
// acceleration towards the air is a_n = -d^2u/dt^2; pressure is positive in compression.
//
// For a Heaviside load P H(t), at distance r and time t,
//   u_H(r, t) = P / (mu r) * S(tau; nu),   tau = c_s t / r,
// with S = 0 before the P front (tau < alpha = c_s/c_p), a one-sided singularity just before the
// Rayleigh front (tau -> x_R = c_s/c_R from below), and S = (1 - nu)/(2 pi) (Boussinesq's static
// value) after it. S is a sum over the three roots y_j of the rationalized Rayleigh function
//   Q(y) = -16 (1 - alpha^2) y^3 + 8 (3 - 2 alpha^2) y^2 - 8 y + 1
// (real, or one real and a conjugate pair for nu above 0.263):
//   S = -(1/2 pi) sum_j [ c_j (1 - R_j(alpha^2)) H(tau - alpha) + d_j (1 - R_j(1)) H(tau - 1) ],
//   R_j(a) = sqrt((y_j - a) / (y_j - tau^2))  (0 once the Rayleigh front has passed),
//   c_j = (1 - 2 y_j)^2 / Q'(y_j),  d_j = 4 y_j (y_j - alpha^2) / Q'(y_j)
// (Mooney 1974's generalization of Pekeris 1955, in Kausel 2013's spirit; our own derivation).
//
// 004's temporal regularization convolves with f_eps = 2 g_eps - g_2eps, g_eps a Lorentzian of
// width eps/c_s in time, i.e. eta = eps/r in tau. A Lorentzian is the Poisson kernel of the upper
// half-plane, so (g * S)(tau) = (1/pi) Im C(tau + i eta), C(zeta) = int S(x) / (x - zeta) dx, and
// every term of S has an elementary Cauchy integral: the regularized field and its time
// derivatives are closed forms in complex logarithms and algebraic functions.
#include <array>
#include <complex>
#include <numbers>

#include "model/material.hpp"

namespace clatter::kernels::ground {

// The half-space is a model::Material (its moduli and density); Lamb's closed form below also needs
// 0 < nu (the sum over the Rayleigh roots assumes it). std::invalid_argument naming the value when
// the material is not one (model::check_material) or nu <= 0.
void check_lamb_ground(const model::Material& ground);

// Pekeris's closed form (nu = 1/4): S(tau) with its explicit constants.
double pekeris_step(double tau);

class LambSurface {
 public:
  // std::invalid_argument for nu outside (0, 0.5).
  explicit LambSurface(double poisson_ratio);

  double poisson_ratio() const { return nu_; }
  double alpha() const { return alpha_; }             // c_s / c_p: the P front, in tau
  double rayleigh_tau() const { return x_rayleigh_; }  // c_s / c_R: the Rayleigh front, in tau
  double static_value() const { return (1 - nu_) / (2 * std::numbers::pi); }

  // S(tau): the dimensionless step response above.
  double step(double tau) const;

  // d^k/dtau^k of (P_eta * S)(tau), P_eta(x) = eta / (pi (x^2 + eta^2)) (the Lorentzian), k = 0..3,
  // eta > 0. In closed form.
  double smoothed(double tau, double eta, int k) const;
  // d^k/dtau^k of (f_eta * S)(tau), f_eta = 2 P_eta - P_2eta (004's f_eps with eta = eps / r).
  double regularized(double tau, double eta, int k) const { return 2 * smoothed(tau, eta, k) - smoothed(tau, 2 * eta, k); }

 private:
  // -(1/2 pi) coefficient * [H(tau - sqrt(a)) - R(tau; root, a)], R cut at the Rayleigh front.
  struct Term {
    std::complex<double> coefficient, root;
    double a;        // alpha^2 (the P family) or 1 (the S family)
    double tau_end;  // where R ends: x_R for the Rayleigh root inside the path, else infinity
  };
  double nu_, alpha_, x_rayleigh_;
  std::array<Term, 6> terms_{};
};

// The regularized normal acceleration of the surface towards the air, per unit impulse (1 N s)
// delivered as 004's smoothed delta of width eps (4 eps = c_s t_c):
//   a_n(r, t) = -(c_s^3 / (mu r^4)) d^3/dtau^3 (f_eta * S)(tau),   tau = c_s t / r, eta = eps / r.
class RegularizedLamb {
 public:
  RegularizedLamb(const model::Material& ground, double epsilon_m);  // check_lamb_ground
  double acceleration(double r_m, double t_s) const;
  // The displacement into the ground per unit impulse, (1/(mu r)) (c_s/r) d/dtau (f_eta * S).
  double displacement(double r_m, double t_s) const;
  const model::Material& ground() const { return ground_; }
  double epsilon_m() const { return epsilon_m_; }

 private:
  model::Material ground_;
  double epsilon_m_, c_s_;
  LambSurface surface_;
};

}  // namespace clatter::kernels::ground
