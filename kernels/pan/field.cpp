#include "kernels/pan/field.hpp"

#include <cmath>
#include <stdexcept>

#include "kernels/fdtd/geometry.hpp"
#include "kernels/pan/directions.hpp"

namespace clatter::kernels::pan {

Series evaluate(const ProxyField& f, const std::array<double, 3>& x_m, double beta, double output_rate_hz,
                Interpolation interpolation) {
  if (!(beta > 0)) throw std::invalid_argument("PAN evaluate: scale beta must be > 0");
  // Eq. (10): P^(beta h)(x, t) = beta^s p^(h)(x / beta, t / beta), s = 1 (translation) or 2 (rotation).
  std::array<double, 3> y{};
  double sign = 1.0;
  for (int a = 0; a < 3; ++a) {
    y[a] = std::abs(x_m[a] / beta);
    if (x_m[a] < 0) sign *= fdtd::field_parity(f.field, a);  // eqs. (16)-(21)
  }
  const double r = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  if (!(r > 0)) throw std::invalid_argument("PAN evaluate: the point is the proxy's centre");
  // Algorithm 1: drop finest levels while the scaled rate exceeds twice the output rate.
  std::size_t n = f.length;
  double rate = 1.0 / f.dt_s, gain = 1.0;
  while (output_rate_hz > 0 && rate / beta > 2.0 * output_rate_hz && n > 2) {
    rate /= 2;
    n /= 2;
    gain /= std::sqrt(2.0);
  }
  std::vector<double> c(n, 0.0);
  const int divisions = divisions_of(f.directions.size());
  if (divisions == 0) throw std::invalid_argument("PAN evaluate: direction count is not an octant triangulation");
  const DirectionWeights w = locate_direction(y, divisions, interpolation);
  double delay = 0;  // the direction's alignment, interpolated like the signals
  for (std::size_t v = 0; v < static_cast<std::size_t>(w.count); ++v) {
    if (w.weight[v] == 0) continue;
    const auto vertex = static_cast<std::size_t>(w.vertex[v]);
    accumulate(f.directions.at(vertex), f.terms, r, w.weight[v], c);
    if (!f.delay_steps.empty()) delay += w.weight[v] * f.delay_steps.at(vertex);
  }
  for (double& x : c) x *= gain;
  const Wavelet wavelet(f.length);
  wavelet.inverse(c);
  const double levels_dropped = std::log2(static_cast<double>(f.length) / static_cast<double>(n));
  const double amplitude = sign * (f.field <= 3 ? beta : beta * beta);
  Series s;
  s.dt_s = beta / rate;
  // Dropping L levels delays the reconstruction by (2^L - 1) filter delays (Wavelet).
  const double lag_s = (std::exp2(levels_dropped) - 1.0) * wavelet.scaling_delay_samples() * f.dt_s;
  s.t0_s = beta * (f.t_first_s + r / f.c_m_s - delay * f.dt_s + lag_s);
  s.p.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.p[i] = amplitude * c[i];
  return s;
}

}  // namespace clatter::kernels::pan
