#include "kernels/pan/render.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "kernels/contact.hpp"
#include "kernels/pulse.hpp"

namespace clatter::kernels::pan {
namespace {

// 10-point Gauss-Legendre on [lo, hi] (the integrands are smooth on each piece).
template <class F>
double gauss10(double lo, double hi, F f) {
  static constexpr double x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244, 0.8650633666889845,
                                  0.9739065285171717};
  static constexpr double w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820, 0.1494513156275533,
                                  0.0666713443086881};
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  double s = 0;
  for (int i = 0; i < 5; ++i) s += w[i] * (f(mid - half * x[i]) + f(mid + half * x[i]));
  return s * half;
}

// The Catmull-Rom cubic of each interval [j, j+1) of q (zero outside), as polynomial coefficients
// in f = u - j: the mix evaluates each interval several times (once per basis weight), so the
// coefficients are worth computing once. Entry 0 is the interval [-1, 0).
void catmull_rom(const std::vector<double>& q, std::vector<std::array<double, 4>>& poly) {
  const long n = static_cast<long>(q.size());
  auto at = [&](long j) { return j >= 0 && j < n ? q[static_cast<std::size_t>(j)] : 0.0; };
  poly.resize(static_cast<std::size_t>(n + 1));
  for (long j = -1; j < n; ++j) {
    const double a = at(j - 1), b = at(j), c = at(j + 1), d = at(j + 2);
    poly[static_cast<std::size_t>(j + 1)] = {b, 0.5 * (c - a), 0.5 * (2 * a - 5 * b + 4 * c - d), 0.5 * (3 * (b - c) + d - a)};
  }
}

}  // namespace

PulseWeights half_sine_weights(double t0, double tau, double step) {
  if (!(tau > 0) || !(step > 0)) throw std::invalid_argument("half_sine_weights: tau and the step must be > 0");
  PulseWeights out;
  out.k_first = static_cast<long>(std::floor(t0 / step)) - 1;
  const long k_last = static_cast<long>(std::ceil((t0 + tau) / step)) + 1;
  const double impulse = 2 * tau / std::numbers::pi;  // integral of S
  if (tau >= 2 * step) {
    // Resolved: interpolate (z_k = S(kH), error O((H/tau)^2)), rescaled so that the impulse is exact.
    double sum = 0;
    for (long k = out.k_first; k <= k_last; ++k) {
      out.z.push_back(half_sine(static_cast<double>(k) * step, t0, tau));
      sum += out.z.back() * step;
    }
    for (double& z : out.z) z *= impulse / sum;
    return out;
  }
  // Shorter than two steps: samples could miss the pulse; project it (keeps the impulse).
  for (long k = out.k_first; k <= k_last; ++k) {
    // psi(t - kH; H) is a cubic on each [kH + jH, kH + (j+1)H], j = -2..1; S is smooth on its support.
    double z = 0;
    const double centre = static_cast<double>(k) * step;
    for (int j = -2; j < 2; ++j) {
      const double lo = std::max(t0, centre + j * step), hi = std::min(t0 + tau, centre + (j + 1) * step);
      if (hi > lo) z += gauss10(lo, hi, [&](double t) { return half_sine(t, t0, tau) * kernels::pulse(t - centre, step); });
    }
    out.z.push_back(z / step);
  }
  return out;
}

void render_impact(const model::PanBankHeader& bank, const model::PanProxy& proxy, double beta,
                   const std::array<double, 3>& x_m, const HalfSineAcceleration& a, double rate_hz, double t_begin_s,
                   std::span<double> out) {
  const Series p = evaluate_sum(bank, proxy, a.peak, x_m, beta, rate_hz);
  const double step = beta * bank.h_s;
  const PulseWeights w = half_sine_weights(a.t0_s, a.tau_s, step);
  thread_local std::vector<std::array<double, 4>> poly;
  catmull_rom(p.p, poly);
  const long last = static_cast<long>(p.p.size());  // intervals [-1, 0) .. [last - 1, last)
  const double span_s = static_cast<double>(last + 1) * p.dt_s, du = 1.0 / (rate_hz * p.dt_s);
  for (std::size_t q = 0; q < w.z.size(); ++q) {  // each shifted, weighted copy of the series
    if (w.z[q] == 0) continue;
    const double z = w.z[q];
    const double shift = static_cast<double>(w.k_first + static_cast<long>(q)) * step + p.t0_s;  // time of q0[0]
    const long n_lo = std::max(0L, static_cast<long>(std::ceil((shift - p.dt_s - t_begin_s) * rate_hz)));
    const long n_hi = std::min(static_cast<long>(out.size()) - 1, static_cast<long>(std::floor((shift + span_s - t_begin_s) * rate_hz)));
    const double u0 = (t_begin_s - shift) / p.dt_s;
    for (long n = n_lo; n <= n_hi; ++n) {
      const double u = u0 + static_cast<double>(n) * du;
      if (!(u >= -1.0)) continue;                     // n_lo rounds down by at most a sample
      const long i = static_cast<long>(u + 1.0) - 1;  // floor for u >= -1, without a libm call
      if (i >= last) break;
      const auto& c = poly[static_cast<std::size_t>(i + 1)];
      const double f = u - static_cast<double>(i);
      out[static_cast<std::size_t>(n)] += z * (c[0] + f * (c[1] + f * (c[2] + f * c[3])));
    }
  }
}

}  // namespace clatter::kernels::pan
