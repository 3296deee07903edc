#include "kernels/fdtd/dispersion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "kernels/pulse.hpp"

namespace clatter::kernels::fdtd {

namespace {

constexpr double kPi = std::numbers::pi;

// psi^(f) = 2 int_0^{2h} psi(t) cos(2 pi f t) dt (psi is even), by composite Simpson on each of
// the two cubic pieces, exact up to the cosine's variation (400 panels over 2h).
double pulse_spectrum(double h_s, double f_hz) {
  constexpr int n = 400;
  const double step = 2.0 * h_s / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double t = i * step, w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * pulse(t, h_s) * std::cos(2 * kPi * f_hz * t);
  }
  return 2.0 * sum * step / 3.0;
}

// sin^2(omega dt / 2) of the scheme for wavenumber k along unit d (cell units folded in).
double symbol(Scheme scheme, double courant, double k_dx, const double (&d)[3]) {
  double s2 = 0, s4 = 0;
  for (double di : d) {
    const double x = std::pow(std::sin(k_dx * di / 2), 2);
    s2 += x;
    s4 += x + x * x / 3;
  }
  const double l2 = courant * courant;
  return scheme == Scheme::srl ? l2 * s2 : l2 * s4 - l2 * l2 / 3 * s2 * s2;
}

}  // namespace

double pulse_band_edge_hz(double h_s) {
  const double dc = pulse_spectrum(h_s, 0);
  double f = 0;
  const double df = 0.002 / h_s;
  while (std::abs(pulse_spectrum(h_s, f)) > 1e-2 * dc && f < 10 / h_s) f += df;
  return f;
}

namespace {

// |psi^(f)|^2 at the midpoints of n bins up to where psi^ is 1e-6 of its peak or the time grid's
// Nyquist frequency: the weights of every direction's error, computed once per solve.
struct Spectrum {
  double f_top = 0;
  std::vector<double> weight;
};

Spectrum pulse_power(double h_s, double dt_s) {
  constexpr int n = 2000;
  Spectrum s;
  s.f_top = std::min(8.0 / h_s, 0.5 / dt_s);
  for (int i = 0; i < n; ++i) {
    const double a = pulse_spectrum(h_s, (i + 0.5) * s.f_top / n);
    s.weight.push_back(a * a);
  }
  return s;
}

double direction_error(const Spectrum& spectrum, Scheme scheme, double courant, double dx_m, double c_m_s,
                       double distance_m, const double (&direction)[3]) {
  const double norm = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  const double d[3] = {direction[0] / norm, direction[1] / norm, direction[2] / norm};
  const double dt = courant * dx_m / c_m_s;
  // The grid carries wavenumbers up to the first zone edge along d; omega(k) rises monotonically
  // there for both schemes below their CFL limits.
  double dmax = 0;
  for (double di : d) dmax = std::max(dmax, std::abs(di));
  const double k_dx_max = kPi / dmax;
  auto omega = [&](double k_dx) {
    const double s = std::clamp(symbol(scheme, courant, k_dx, d), 0.0, 1.0);
    return 2.0 * std::asin(std::sqrt(s)) / dt;
  };
  const double omega_max = omega(k_dx_max);
  const std::size_t n = spectrum.weight.size();
  double num = 0, den = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = (static_cast<double>(i) + 0.5) * spectrum.f_top / static_cast<double>(n), w = 2 * kPi * f;
    const double weight = spectrum.weight[i];
    den += weight;
    if (w >= omega_max) {  // not carried by the grid in this direction
      num += weight;
      continue;
    }
    double lo = 0, hi = k_dx_max;  // omega(k) = w by bisection
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (omega(mid) < w ? lo : hi) = mid;
    }
    const double dk = 0.5 * (lo + hi) / dx_m - w / c_m_s;
    num += weight * std::norm(std::polar(1.0, -dk * distance_m) - 1.0);
  }
  return std::sqrt(num / den);
}

}  // namespace

double dispersion_error(Scheme scheme, double courant, double dx_m, double c_m_s, double h_s, double distance_m,
                        const double (&direction)[3]) {
  const Spectrum spectrum = pulse_power(h_s, courant * dx_m / c_m_s);
  return direction_error(spectrum, scheme, courant, dx_m, c_m_s, distance_m, direction);
}

double worst_dispersion_error(Scheme scheme, double courant, double dx_m, double c_m_s, double h_s, double distance_m) {
  const Spectrum spectrum = pulse_power(h_s, courant * dx_m / c_m_s);
  double worst = 0;
  for (const auto& d : {std::array<double, 3>{1, 0, 0}, std::array<double, 3>{1, 1, 0}, std::array<double, 3>{1, 1, 1}}) {
    const double dir[3] = {d[0], d[1], d[2]};
    worst = std::max(worst, direction_error(spectrum, scheme, courant, dx_m, c_m_s, distance_m, dir));
  }
  return worst;
}

}  // namespace clatter::kernels::fdtd
