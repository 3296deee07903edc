#pragma once
// Small helpers the reference comparisons share: a relative L2 error and the half-sine
// acceleration (F_max / m) S(t; t0, tau) as the exact translating sphere wants its A(t).
#include <cmath>
#include <cstddef>
#include <vector>

#include "kernels/contact.hpp"

namespace clatter::reference {

// Relative L2 of samples against a reference evaluated at each sample index.
template <class Want>
double relative_l2(const std::vector<double>& got, Want want) {
  double num = 0, den = 0;
  for (std::size_t n = 0; n < got.size(); ++n) {
    const double w = want(n);
    num += (got[n] - w) * (got[n] - w);
    den += w * w;
  }
  return std::sqrt(num / den);
}

struct HalfSine {
  double peak, t0, tau;
};
// The acceleration callback of translating_sphere_pressure; context: a HalfSine.
inline double half_sine_acceleration(double t, const void* context) {
  const auto* h = static_cast<const HalfSine*>(context);
  return h->peak * kernels::half_sine(t, h->t0, h->tau);
}

}  // namespace clatter::reference
