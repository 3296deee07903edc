#include "kernels/pan/field.hpp"

#include <cmath>
#include <stdexcept>

#include "kernels/fdtd/geometry.hpp"
#include "kernels/pan/directions.hpp"

namespace clatter::kernels::pan {

Series evaluate(const ProxyField& f, const std::array<double, 3>& x_m, double beta, double output_rate_hz,
                Interpolation interpolation) {
  return evaluate_sum({&f, nullptr, nullptr, nullptr, nullptr, nullptr}, {1, 0, 0, 0, 0, 0}, x_m, beta, output_rate_hz,
                      interpolation);
}

Series evaluate_sum(const std::array<const ProxyField*, 6>& fields, const std::array<double, 6>& weights,
                    const std::array<double, 3>& x_m, double beta, double output_rate_hz, Interpolation interpolation) {
  if (!(beta > 0)) throw std::invalid_argument("PAN evaluate: scale beta must be > 0");
  const ProxyField* first = nullptr;
  for (const auto* f : fields)
    if (f && !first) first = f;
  if (!first) throw std::invalid_argument("PAN evaluate: no field given");
  // Eq. (10): P^(beta h)(x, t) = beta^s p^(h)(x / beta, t / beta), s = 1 (translation) or 2 (rotation).
  std::array<double, 3> y{};
  for (int a = 0; a < 3; ++a) y[a] = std::abs(x_m[a] / beta);
  const double r = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  if (!(r > 0)) throw std::invalid_argument("PAN evaluate: the point is the proxy's centre");
  // Algorithm 1: drop finest levels while the scaled rate exceeds twice the output rate.
  std::size_t n = first->length;
  double rate = 1.0 / first->dt_s, gain = 1.0;
  while (output_rate_hz > 0 && rate / beta > 2.0 * output_rate_hz && n > 2) {
    rate /= 2;
    n /= 2;
    gain /= std::sqrt(2.0);
  }
  std::vector<double> c(n, 0.0);
  const int divisions = divisions_of(first->directions.size());
  if (divisions == 0) throw std::invalid_argument("PAN evaluate: direction count is not an octant triangulation");
  const DirectionWeights w = locate_direction(y, divisions, interpolation);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const ProxyField* f = fields[i];
    if (!f || weights[i] == 0) continue;
    if (f->length != first->length || f->directions.size() != first->directions.size() || f->dt_s != first->dt_s)
      throw std::invalid_argument("PAN evaluate: fields of different proxies or banks");
    double sign = 1.0;  // eqs. (16)-(21)
    for (int a = 0; a < 3; ++a)
      if (x_m[a] < 0) sign *= fdtd::field_parity(f->field, a);
    const double scale = weights[i] * sign * (f->field <= 3 ? beta : beta * beta) * gain;
    for (std::size_t v = 0; v < static_cast<std::size_t>(w.count); ++v)
      if (w.weight[v] != 0)
        accumulate(f->directions.at(static_cast<std::size_t>(w.vertex[v])), f->terms, r, scale * w.weight[v], c);
  }
  double delay = 0;  // the direction's alignment, interpolated like the signals
  if (!first->delay_steps.empty())
    for (std::size_t v = 0; v < static_cast<std::size_t>(w.count); ++v)
      delay += w.weight[v] * first->delay_steps.at(static_cast<std::size_t>(w.vertex[v]));
  const Wavelet& wavelet = cached_wavelet(first->length);
  wavelet.inverse(c);
  const double levels_dropped = std::log2(static_cast<double>(first->length) / static_cast<double>(n));
  Series s;
  s.dt_s = beta / rate;
  // Dropping L levels delays the reconstruction by (2^L - 1) filter delays (Wavelet).
  const double lag_s = (std::exp2(levels_dropped) - 1.0) * wavelet.scaling_delay_samples() * first->dt_s;
  s.t0_s = beta * (first->t_first_s + r / first->c_m_s - delay * first->dt_s + lag_s);
  s.p = std::move(c);
  return s;
}

}  // namespace clatter::kernels::pan
