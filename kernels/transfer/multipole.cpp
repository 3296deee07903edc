#include "kernels/transfer/multipole.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/transfer/special_functions.hpp"

namespace clatter::kernels::transfer {

namespace {

// sum_n h_n sum_m M_n^m Y_n^m in real arithmetic: std::complex products check for NaN on every
// term (no -fcx-limited-range).
std::complex<double> expansion_sum(const Multipole& m, const std::complex<double>* h, const std::complex<double>* y) {
  double p_re = 0, p_im = 0;
  for (int n = 0; n <= m.order; ++n) {
    double s_re = 0, s_im = 0;
    for (int i = harmonic_index(n, -n); i <= harmonic_index(n, n); ++i) {
      const std::complex<double> c = m.coefficients[static_cast<std::size_t>(i)], v = y[i];
      s_re += c.real() * v.real() - c.imag() * v.imag();
      s_im += c.real() * v.imag() + c.imag() * v.real();
    }
    p_re += h[n].real() * s_re - h[n].imag() * s_im;
    p_im += h[n].real() * s_im + h[n].imag() * s_re;
  }
  return {p_re, p_im};
}

}  // namespace

std::complex<double> Multipole::pressure(const Eigen::Vector3d& x_m) const {
  const double r = x_m.norm();
  const auto h = spherical_hankel2(order, k_rad_m * r);
  std::vector<std::complex<double>> y(static_cast<std::size_t>(harmonic_count(order)));
  spherical_harmonics(order, x_m.z() / r, std::atan2(x_m.y(), x_m.x()), y.data());
  return expansion_sum(*this, h.data(), y.data());
}

void pressure_magnitudes(std::span<const Multipole* const> modes, const Eigen::Vector3d& x_m, double* out) {
  int top = 0;
  for (const Multipole* m : modes) top = std::max(top, m->order);
  const double r = x_m.norm();
  std::vector<std::complex<double>> y(static_cast<std::size_t>(harmonic_count(top))), h(static_cast<std::size_t>(top) + 1);
  spherical_harmonics(top, x_m.z() / r, std::atan2(x_m.y(), x_m.x()), y.data());
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const Multipole& m = *modes[k];
    spherical_hankel2_upward(m.order, m.k_rad_m * r, h.data());
    out[k] = std::abs(expansion_sum(m, h.data(), y.data()));
  }
}

double far_field_power_w(const Multipole& m, double rho, double c) {
  double sum = 0;
  for (const auto& coefficient : m.coefficients) sum += std::norm(coefficient);
  return sum / (2 * rho * c * m.k_rad_m * m.k_rad_m);
}

void add_monopole(double k_rad_m, int order, const Eigen::Vector3d& y_m, std::complex<double> strength,
                  std::vector<std::complex<double>>& coefficients) {
  const double r = y_m.norm();
  const auto j = spherical_bessel_j(order, k_rad_m * r);
  std::vector<std::complex<double>> y(static_cast<std::size_t>(harmonic_count(order)));
  if (r > 0)
    spherical_harmonics(order, y_m.z() / r, std::atan2(y_m.y(), y_m.x()), y.data());
  else
    spherical_harmonics(order, 1.0, 0.0, y.data());
  const std::complex<double> factor = std::complex<double>(0, -k_rad_m) * strength;
  for (int n = 0; n <= order; ++n) {
    const std::complex<double> fn = factor * j[static_cast<std::size_t>(n)];
    for (int m = -n; m <= n; ++m) {
      const auto i = static_cast<std::size_t>(harmonic_index(n, m));
      coefficients[i] += fn * std::conj(y[i]);
    }
  }
}

void add_mirrored_monopole(double k_rad_m, int order, const Eigen::Vector3d& y_m,
                           std::span<const std::complex<double>> strengths, std::span<const int> sigmas,
                           std::vector<std::complex<double>>& coefficients) {
  const double r = y_m.norm();
  const auto j = spherical_bessel_j(order, k_rad_m * r);
  std::vector<std::complex<double>> y(static_cast<std::size_t>(harmonic_count(order)));
  spherical_harmonics(order, r > 0 ? y_m.z() / r : 1.0, std::atan2(y_m.y(), y_m.x()), y.data());
  for (std::size_t c = 0; c < sigmas.size(); ++c) {
    const int sigma = sigmas[c];
    const double sx = (sigma & 1) ? -1 : 1, sy = (sigma & 2) ? -1 : 1, sz = (sigma & 4) ? -1 : 1;
    const std::complex<double> factor = std::complex<double>(0, -k_rad_m) * strengths[c];
    for (int n = 0; n <= order; ++n) {
      const std::complex<double> fn = factor * j[static_cast<std::size_t>(n)];
      for (int m = -n; m <= n; ++m) {
        const double pm = (m % 2) ? -1.0 : 1.0, pz = ((n + m) % 2) ? -1.0 : 1.0;
        const double z_part = 1 + sz * pz;
        if (z_part == 0) continue;
        const auto i = static_cast<std::size_t>(harmonic_index(n, m));
        // sum_s sign(s) conj Y(mirror_s y-hat) = (1 + sz (-1)^(n+m)) [conj Y (1 + sx sy (-1)^m) + Y (sx (-1)^m + sy)].
        const std::complex<double> images = std::conj(y[i]) * (1 + sx * sy * pm) + y[i] * (sx * pm + sy);
        coefficients[i] += fn * z_part * images;
      }
    }
  }
}

int source_order(double k_rad_m, double rho_m) {
  const double kr = k_rad_m * rho_m;
  return static_cast<int>(std::ceil(kr + 3 * std::cbrt(kr) + 20));
}

int truncation_order(const std::vector<std::complex<double>>& coefficients, int order, double tolerance) {
  std::vector<double> energy(static_cast<std::size_t>(order) + 1, 0.0);
  double total = 0;
  for (int n = 0; n <= order; ++n)
    for (int m = -n; m <= n; ++m) energy[static_cast<std::size_t>(n)] += std::norm(coefficients[static_cast<std::size_t>(harmonic_index(n, m))]);
  for (double e : energy) total += e;
  double tail = 0;
  for (int n = order; n > 0; --n) {
    tail += energy[static_cast<std::size_t>(n)];
    if (tail > tolerance * tolerance * total) return n;
  }
  return 0;
}

Multipole stored_multipole(const model::ModalTransfer& t, std::size_t mode) {
  Multipole m{t.wavenumber_rad_m.at(mode), t.order.at(mode), {}};
  const std::size_t at = t.offset(mode), count = static_cast<std::size_t>(harmonic_count(m.order));
  m.coefficients.reserve(count);
  for (std::size_t i = at; i < at + count; ++i) m.coefficients.emplace_back(t.coefficients[2 * i], t.coefficients[2 * i + 1]);
  return m;
}

Multipole scaled(const Multipole& m, double gamma) {
  Multipole s = m;
  s.k_rad_m = m.k_rad_m / gamma;
  const double factor = std::pow(gamma, -2.5);
  for (auto& c : s.coefficients) c *= factor;
  return s;
}

}  // namespace clatter::kernels::transfer
