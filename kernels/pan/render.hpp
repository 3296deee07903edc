#pragma once
// Acceleration noise of one impact from a PAN proxy (Chadwick et al. 2012, eq. 15):
//   p(x, t) = sum_k sum_i z_i(k beta h) P_i^(beta h)(x, t - k beta h)
// for a proxy scaled by beta, whose rigid-body accelerations are z_i(t) = peak_i S(t; t0, tau)
// (translations along, then rotations about, the proxy's axes). All six fields share the time
// profile, so they are summed in coefficient space first (one inverse transform per impact).
#include <array>
#include <span>

#include "kernels/pan/field.hpp"

namespace clatter::kernels::pan {

struct HalfSineAcceleration {
  double t0_s = 0, tau_s = 0;
  std::array<double, 6> peak{};  // m/s^2 (i = 1..3) and rad/s^2 (i = 4..6), proxy frame
};

// The weights z_k of the basis psi(t - k H; H), H = beta h, for z(t) = S(t; t0, tau), such that
// sum_k z_k H = integral S dt = 2 tau / pi exactly (the impact's momentum):
// - tau >= 2H: the samples S(kH) (sum_k S(kH) psi(t - kH) reproduces S up to O((H/tau)^2);
//   psi is a partition of unity), rescaled by the ratio of the exact to the sampled impulse;
// - shorter: the projections (1/H) integral S(t) psi(t - kH; H) dt, which keep the impulse for any
//   tau since psi is a partition of unity (samples could miss the pulse). They smooth twice, which
//   is why longer pulses are sampled: at tau = 10 H projection gave 4.5 % against the exact sphere,
//   sampling 1.6 % (PanRender test).
struct PulseWeights {
  long k_first = 0;
  std::vector<double> z;
};
PulseWeights half_sine_weights(double t0_s, double tau_s, double step_s);

// Adds the impact's pressure at x (proxy frame, metres, outside the scaled bounding sphere) into
// `out`, whose sample n is at t_begin_s + n / rate_hz. Samples outside `out` are dropped. The
// proxy's solved fields all radiate (a.peak[i] weighs field i + 1); the pulse basis step is the
// bank's h_s scaled by beta.
void render_impact(const model::PanBankHeader& bank, const model::PanProxy& proxy, double beta,
                   const std::array<double, 3>& x_m, const HalfSineAcceleration& a, double rate_hz, double t_begin_s,
                   std::span<double> out);

}  // namespace clatter::kernels::pan
