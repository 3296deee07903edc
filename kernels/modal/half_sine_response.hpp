#pragma once
// One mode's exact response to the half-sine contact force of the synthesizer (the Hertz pulse of
// kernels/contact.hpp, 003 Algorithm 1): q'' + 2 xi omega q' + omega^2 q = G sin(pi t / tau) on
// [0, tau], from rest. With the pole s = -xi omega + i omega_d and the impulse response
// e^{-xi omega t} sin(omega_d t) / omega_d = Im(e^{s t}) / omega_d,
//   q(t) = (G / omega_d) Im(e^{s t} I(min(t, tau))),  I(T) = int_0^T sin(pi t' / tau) e^{-s t'} dt',
// and I has a closed form, so q is exact at every sample (no time stepping during contact); after
// the contact q(t) = Im(C e^{s t}) with the constant phasor C, a damped sinusoid that a two-pole
// recursion carries exactly (kernels/modal/resonator_bank.hpp).
#include <complex>
#include <cstddef>

namespace clatter::kernels::modal {

class HalfSineResponse {
 public:
  // omega_rad_s > 0, 0 <= xi < 1 (an underdamped mode), tau_s > 0; amplitude: G, the modal force
  // peak u.f [N kg^-1/2 for mass-normalized shapes].
  HalfSineResponse(double omega_rad_s, double xi, double tau_s, double amplitude);

  double at(double t_s) const;                      // q(t) since the contact began, 0 for t < 0
  // out[n] += weight q(t_first + n dt) for n < count, all within [0, tau]: e^{s t} I(t) is a sum of
  // three exponentials, (e^{i W t} - e^{s t}) / a - (e^{-i W t} - e^{s t}) / b over 2i with
  // a, b = +-i W - s, so consecutive samples cost three complex products instead of exponentials.
  void add_contact_samples(double t_first_s, double dt_s, std::size_t count, double weight, double* out) const;
  // The mode's energy when the contact ends, (q'^2 + omega^2 q^2) / 2 at t = tau [J for
  // mass-normalized shapes]: what the contact put into it, less the damping's share during it.
  double energy_after_contact_j() const;
  // int_tau^inf q(t)^2 dt [s per unit q^2]: the free ring's square integral, in closed form from
  // Im(z)^2 = (|z|^2 - Re z^2) / 2 with z = C e^{s t}. A listener whose pressure is w q(t) hears
  // w^2 times it; the mode's far-field power P per unit q^2 (time-averaged, so 2 P q^2 at the
  // instant) radiates 2 P times it.
  double free_square_integral() const;
  std::complex<double> free_phasor() const { return free_; }  // C: q(t) = Im(C e^{s t}) for t >= tau
  std::complex<double> pole() const { return s_; }  // s [1/s]
  double contact_time_s() const { return tau_s_; }

 private:
  std::complex<double> integral(double t_s) const;  // I(t) for 0 <= t <= tau

  std::complex<double> s_, free_;
  double tau_s_ = 0, omega_force_ = 0, gain_ = 0;  // gain: G / omega_d
};

}  // namespace clatter::kernels::modal
