#include "kernels/pan/field.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "kernels/fdtd/geometry.hpp"
#include "kernels/pan/direction_mesh.hpp"
#include "kernels/pan/directions.hpp"
#include "kernels/pan/fit.hpp"
#include "kernels/pan/radial.hpp"
#include "kernels/pan/wavelet.hpp"

namespace clatter::kernels::pan {

Series evaluate(const FieldView& f, const std::array<double, 3>& x_m, double beta, double output_rate_hz,
                Interpolation interpolation) {
  if (!f.bank || !f.proxy || f.field < 1 || f.field > 6) throw std::invalid_argument("PAN evaluate: no field given");
  if (!f.proxy->solved(f.field)) throw std::invalid_argument("PAN evaluate: the field was not solved");
  std::array<double, 6> weights{};
  weights[static_cast<std::size_t>(f.field - 1)] = 1;
  return evaluate_sum(*f.bank, *f.proxy, weights, x_m, beta, output_rate_hz, interpolation);
}

Series evaluate_sum(const model::PanBankHeader& bank, const model::PanProxy& proxy, const std::array<double, 6>& weights,
                    const std::array<double, 3>& x_m, double beta, double output_rate_hz, Interpolation interpolation) {
  if (!(beta > 0)) throw std::invalid_argument("PAN evaluate: scale beta must be > 0");
  bool any = false;
  for (int field = 1; field <= 6; ++field) any = any || proxy.solved(field);
  if (!any) throw std::invalid_argument("PAN evaluate: no field given");
  // Eq. (10): P^(beta h)(x, t) = beta^s p^(h)(x / beta, t / beta), s = 1 (translation) or 2 (rotation).
  std::array<double, 3> y{};
  for (int a = 0; a < 3; ++a) y[a] = std::abs(x_m[a] / beta);
  const double r = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  if (!(r > 0)) throw std::invalid_argument("PAN evaluate: the point is the proxy's centre");
  // Algorithm 1: drop finest levels while the scaled rate exceeds twice the output rate.
  std::size_t n = bank.length;
  double rate = 1.0 / bank.dt_s, gain = 1.0;
  while (output_rate_hz > 0 && rate / beta > 2.0 * output_rate_hz && n > 2) {
    rate /= 2;
    n /= 2;
    gain /= std::sqrt(2.0);
  }
  std::vector<double> c(n, 0.0);
  const RadialWeights radial = radial_weights(bank.radii_m, r);
  // An entry of eight octants stores each octant's field as it is; a mirror-symmetric one the
  // positive octant's, over its symmetry zeros, the others by parity.
  const bool all_octants = proxy.octants() == 8;
  const int octant = all_octants ? model::octant_of(x_m) : 0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const int field = static_cast<int>(i) + 1;
    if (!proxy.solved(field) || weights[i] == 0) continue;
    const model::PanField& f = proxy.field(field, octant);
    const DirectionWeights w = locate(bank.divisions, f.directions, y, interpolation);  // each field its own set
    double sign = 1.0;  // eqs. (16)-(21)
    for (int a = 0; a < 3 && !all_octants; ++a)
      if (x_m[a] < 0) sign *= fdtd::field_parity(field, a);
    // The bank stores the field over its symmetry zeros (directions.hpp symmetry_zeros).
    const double zeros = all_octants ? 1.0 : symmetry_zeros(field, {y[0] / r, y[1] / r, y[2] / r});
    const double scale = weights[i] * sign * zeros * (field <= 3 ? beta : beta * beta) * gain;
    for (std::size_t v = 0; v < static_cast<std::size_t>(w.count); ++v)
      if (w.weight[v] != 0)
        accumulate(f.terms.at(static_cast<std::size_t>(w.vertex[v])), bank.values(), radial, scale * w.weight[v], c);
  }
  // Every direction was stored aligned by its support distance (fit.hpp): shift by the query's.
  const double delay =
      support_delay_samples(model::in_octant({y[0] / r, y[1] / r, y[2] / r}, octant), bank.a_m, proxy, bank.c_m_s, bank.dt_s);
  const Wavelet& wavelet = cached_wavelet(bank.length);
  wavelet.inverse(c);
  const double levels_dropped = std::log2(static_cast<double>(bank.length) / static_cast<double>(n));
  Series s;
  s.dt_s = beta / rate;
  // Dropping L levels delays the reconstruction by (2^L - 1) filter delays (Wavelet).
  const double lag_s = (std::exp2(levels_dropped) - 1.0) * wavelet.scaling_delay_samples() * bank.dt_s;
  s.t0_s = beta * (bank.t_first_s + r / bank.c_m_s - delay * bank.dt_s + lag_s);
  s.p = std::move(c);
  return s;
}

}  // namespace clatter::kernels::pan

namespace clatter::kernels::pan {

void check_direction_sets(const model::PanBank& bank) {
  for (std::size_t p = 0; p < bank.proxies.size(); ++p)
    for (int o = 0; o < bank.proxies[p].octants(); ++o)
      for (int field = 1; field <= 6; ++field) {
        const model::PanField& f = bank.proxies[p].field(field, o);
        if (f.solved() != bank.proxies[p].solved(field))  // the evaluator reads whichever octant a point is in
          throw std::invalid_argument("proxy " + std::to_string(p) + " field " + std::to_string(field) + " is solved in "
                                      "octant 0 but not in octant " + std::to_string(o) + ", or the other way round");
        if (!f.solved()) continue;
        try {
          const DirectionMesh mesh(bank.header.divisions, bank.header.max_levels, f.directions);
          if (mesh.size() != f.terms.size()) throw std::invalid_argument("one set of terms per vertex needed");
        } catch (const std::invalid_argument& e) {
          throw std::invalid_argument("proxy " + std::to_string(p) + " field " + std::to_string(field) +
                                      (o > 0 ? " octant " + std::to_string(o) : std::string()) +
                                      ": its direction set is not a refinement of the layout: " + e.what());
        }
      }
}

}  // namespace clatter::kernels::pan
