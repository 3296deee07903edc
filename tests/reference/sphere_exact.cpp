#include "tests/reference/sphere_exact.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "kernels/pulse.hpp"

namespace clatter::reference {
namespace {

// 20-point Gauss-Legendre on [-1, 1].
constexpr std::array<double, 10> kNodes = {0.0765265211334973, 0.2277858511416451, 0.3737060887154195,
                                           0.5108670019508271, 0.6360536807265150, 0.7463319064601508,
                                           0.8391169718222188, 0.9122344282513259, 0.9639719272779138,
                                           0.9931285991850949};
constexpr std::array<double, 10> kWeights = {0.1527533871307258, 0.1491729864726037, 0.1420961093183820,
                                             0.1316886384491766, 0.1181945319615184, 0.1019301198172404,
                                             0.0832767415767048, 0.0626720483341091, 0.0406014298003869,
                                             0.0176140071391521};

// Integral over [lo, hi] of f, with f smooth there.
template <class F>
double gauss(double lo, double hi, F f) {
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  double s = 0;
  for (std::size_t i = 0; i < kNodes.size(); ++i) s += kWeights[i] * (f(mid - half * kNodes[i]) + f(mid + half * kNodes[i]));
  return s * half;
}

}  // namespace

double TranslatingSphere::pressure(double r, double cos_theta, double t) const {
  const double w = c_m_s / radius_m;
  const double tau = t - (r - radius_m) / c_m_s;
  // psi is a cubic on each of [-2h,-h], [-h,0], [0,h], [h,2h]: integrate piece by piece.
  double f = 0, df = 0;
  for (int piece = -2; piece < 2; ++piece) {
    const double lo = piece * h_s, hi = std::min((piece + 1) * h_s, tau);
    if (hi <= lo) continue;
    f += gauss(lo, hi, [&](double s) {
      const double u = tau - s;
      return kernels::pulse(s, h_s) * std::exp(-w * u) * std::sin(w * u) / w;
    });
    df += gauss(lo, hi, [&](double s) {
      const double u = tau - s;
      return kernels::pulse(s, h_s) * std::exp(-w * u) * (std::cos(w * u) - std::sin(w * u));
    });
  }
  const double scale = -rho_kg_m3 * c_m_s * c_m_s * radius_m;
  f *= scale;
  df *= scale;
  return -cos_theta * (f / (r * r) + df / (c_m_s * r));
}

double translating_sphere_pressure(double a, double c, double rho, double r, double cos_theta, double t,
                                   double (*accel)(double, const void*), const void* ctx, double begin, double end,
                                   int pieces) {
  const double w = c / a;
  const double tau = t - (r - a) / c;
  double f = 0, df = 0;
  const double width = (end - begin) / pieces;
  for (int piece = 0; piece < pieces; ++piece) {
    const double lo = begin + piece * width, hi = std::min(begin + (piece + 1) * width, tau);
    if (hi <= lo) continue;
    f += gauss(lo, hi, [&](double s) {
      const double u = tau - s;
      return accel(s, ctx) * std::exp(-w * u) * std::sin(w * u) / w;
    });
    df += gauss(lo, hi, [&](double s) {
      const double u = tau - s;
      return accel(s, ctx) * std::exp(-w * u) * (std::cos(w * u) - std::sin(w * u));
    });
  }
  const double scale = -rho * c * c * a;
  return -cos_theta * (scale * f / (r * r) + scale * df / (c * r));
}

}  // namespace clatter::reference
