#include "kernels/modal/half_sine_response.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace clatter::kernels::modal {
namespace {

// (e^{z T} - 1) / z, continued to T at z = 0: a mode tuned to the pulse (z = i Omega - s -> 0 for
// an undamped mode at omega = pi / tau) must not divide by zero.
std::complex<double> expm1_over(std::complex<double> z, double t) {
  const std::complex<double> zt = z * t;
  if (std::abs(zt) > 1e-4) return (std::exp(zt) - 1.0) / z;
  return t * (1.0 + zt / 2.0 + zt * zt / 6.0 + zt * zt * zt / 24.0);  // truncation below 1e-20
}

}  // namespace

HalfSineResponse::HalfSineResponse(double omega, double xi, double tau, double amplitude) {
  if (!(omega > 0) || !(xi >= 0 && xi < 1) || !(tau > 0))
    throw std::invalid_argument("HalfSineResponse: needs omega > 0, 0 <= xi < 1 and tau > 0");
  const double omega_d = omega * std::sqrt(1 - xi * xi);
  s_ = {-xi * omega, omega_d};
  tau_s_ = tau;
  omega_force_ = std::numbers::pi / tau;
  gain_ = amplitude / omega_d;
  free_ = gain_ * integral(tau);
}

// sin(W t) = (e^{iWt} - e^{-iWt}) / 2i, so I(T) = [E(iW - s) - E(-iW - s)] / 2i with E(z) = (e^{zT} - 1) / z.
std::complex<double> HalfSineResponse::integral(double t) const {
  const std::complex<double> i{0, 1};
  return (expm1_over(i * omega_force_ - s_, t) - expm1_over(-i * omega_force_ - s_, t)) / (2.0 * i);
}

double HalfSineResponse::energy_after_contact_j() const {
  const std::complex<double> z = free_ * std::exp(s_ * tau_s_);
  const double q = z.imag(), q_dot = (s_ * z).imag(), omega_sq = std::norm(s_);  // |s| = omega
  return 0.5 * (q_dot * q_dot + omega_sq * q * q);
}

double HalfSineResponse::free_square_integral() const {
  const std::complex<double> z = free_ * std::exp(s_ * tau_s_);  // int_tau^inf e^{2 s t} = -e^{2 s tau} / (2 s)
  return 0.5 * (std::norm(z) / (-2 * s_.real()) - (z * z / (-2.0 * s_)).real());
}

double HalfSineResponse::at(double t) const {
  if (!(t > 0)) return 0;
  if (t >= tau_s_) return (free_ * std::exp(s_ * t)).imag();
  return gain_ * (std::exp(s_ * t) * integral(t)).imag();
}

void HalfSineResponse::add_contact_samples(double t0, double dt, std::size_t count, double weight, double* out) const {
  const std::complex<double> i{0, 1}, a = i * omega_force_ - s_, b = -i * omega_force_ - s_;
  // A mode tuned to the pulse (|a tau| small) has a -> 0: the closed form per sample keeps the limit.
  if (std::abs(a) * tau_s_ < 1e-3 || std::abs(b) * tau_s_ < 1e-3) {
    for (std::size_t n = 0; n < count; ++n) out[n] += weight * at(t0 + static_cast<double>(n) * dt);
    return;
  }
  const std::complex<double> c = gain_ * weight / (2.0 * i), ca = c / a, cb = c / b;
  std::complex<double> forced = std::exp(i * omega_force_ * t0), decay = std::exp(s_ * t0);
  const std::complex<double> forced_step = std::exp(i * omega_force_ * dt), decay_step = std::exp(s_ * dt);
  for (std::size_t n = 0; n < count; ++n) {
    out[n] += (ca * (forced - decay) - cb * (std::conj(forced) - decay)).imag();
    forced *= forced_step;
    decay *= decay_step;
  }
}

}  // namespace clatter::kernels::modal
