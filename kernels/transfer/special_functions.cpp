#include "kernels/transfer/special_functions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace clatter::kernels::transfer {

std::vector<double> spherical_bessel_j(int n_max, double x) {
  std::vector<double> j(static_cast<std::size_t>(n_max) + 1, 0.0);
  if (x == 0) {
    j[0] = 1;
    return j;
  }
  // Start well above both n_max and x: the ratio j_{n+1} / j_n is then tiny and the start's error
  // dies out going down (each step below n ~ x multiplies it by about x / 2n).
  const int start = std::max(n_max, static_cast<int>(x)) + 32 + static_cast<int>(8 * std::cbrt(x + 1));
  std::vector<double> f(static_cast<std::size_t>(start) + 2, 0.0);
  f[static_cast<std::size_t>(start)] = 1e-300;
  for (int n = start; n >= 1; --n) {
    const auto u = static_cast<std::size_t>(n);
    f[u - 1] = (2.0 * n + 1) / x * f[u] - f[u + 1];
    if (std::abs(f[u - 1]) > 1e200)
      for (std::size_t m = u - 1; m < f.size(); ++m) f[m] *= 1e-200;
  }
  double largest = 0, sum = 0;
  for (double v : f) largest = std::max(largest, std::abs(v));
  for (double& v : f) v /= largest;  // the sum of squares below stays in range
  for (std::size_t n = 0; n < f.size(); ++n) sum += (2.0 * static_cast<double>(n) + 1) * f[n] * f[n];
  // The sign from j_0 = sin x / x or j_1 = sin x / x^2 - cos x / x, whichever is farther from a zero.
  const double j0 = std::sin(x) / x, j1 = std::sin(x) / (x * x) - std::cos(x) / x;
  const bool use0 = std::abs(j0) > std::abs(j1);
  const double scale = std::copysign(1.0 / std::sqrt(sum), use0 ? f[0] * j0 : f[1] * j1);
  for (std::size_t n = 0; n < j.size(); ++n) j[n] = f[n] * scale;
  return j;
}

std::vector<double> spherical_bessel_y(int n_max, double x) {
  std::vector<double> y(static_cast<std::size_t>(n_max) + 1);
  y[0] = -std::cos(x) / x;
  if (n_max >= 1) y[1] = -std::cos(x) / (x * x) - std::sin(x) / x;
  for (int n = 1; n < n_max; ++n) {
    const double next = (2.0 * n + 1) / x * y[static_cast<std::size_t>(n)] - y[static_cast<std::size_t>(n) - 1];
    y[static_cast<std::size_t>(n) + 1] = std::isfinite(next) ? next : -std::numeric_limits<double>::infinity();
  }
  return y;
}

std::vector<std::complex<double>> spherical_hankel2(int n_max, double x) {
  const auto j = spherical_bessel_j(n_max, x);
  const auto y = spherical_bessel_y(n_max, x);
  std::vector<std::complex<double>> h(j.size());
  for (std::size_t n = 0; n < h.size(); ++n) h[n] = {j[n], -y[n]};
  return h;
}

void spherical_hankel2_upward(int n_max, double x, std::complex<double>* out) {
  const std::complex<double> e = std::exp(std::complex<double>(0, -x)) / x;
  out[0] = std::complex<double>(0, 1) * e;
  if (n_max >= 1) out[1] = std::complex<double>(-1, 1 / x) * e;
  for (int n = 1; n < n_max; ++n) out[n + 1] = (2.0 * n + 1) / x * out[n] - out[n - 1];
}

std::vector<std::complex<double>> spherical_hankel2_derivative(const std::vector<std::complex<double>>& h, double x) {
  std::vector<std::complex<double>> d(h.size());
  if (h.empty()) return d;
  // h_0' = -h_1; with only h_0 known, h_1 = h_0 / x - i... from h_0 = i e^{-ix} / x: h_0' = h_0 (-i - 1/x).
  d[0] = h.size() > 1 ? -h[1] : h[0] * std::complex<double>(-1.0 / x, -1.0);
  for (std::size_t n = 1; n < h.size(); ++n) d[n] = h[n - 1] - (static_cast<double>(n) + 1) / x * h[n];
  return d;
}

namespace {

// The recurrence's coefficients a_nm = sqrt((4n^2 - 1) / (n^2 - m^2)) and
// b_nm = sqrt(((n-1)^2 - m^2) / (4 (n-1)^2 - 1)) at harmonic_index(n, m), grown on demand per thread
// (evaluation at a listener is the synthesizer's inner loop: no square roots there).
struct RecurrenceTable {
  int order = -1;
  std::vector<double> a, b;
  void reserve(int n_max) {
    if (n_max <= order) return;
    a.assign(static_cast<std::size_t>(harmonic_count(n_max)), 0.0);
    b.assign(a.size(), 0.0);
    for (int n = 2; n <= n_max; ++n)
      for (int m = 0; m <= n - 2; ++m) {
        const double nn = n, mm = m;
        a[static_cast<std::size_t>(harmonic_index(n, m))] = std::sqrt((4 * nn * nn - 1) / (nn * nn - mm * mm));
        b[static_cast<std::size_t>(harmonic_index(n, m))] =
            std::sqrt(((nn - 1) * (nn - 1) - mm * mm) / (4 * (nn - 1) * (nn - 1) - 1));
      }
    order = n_max;
  }
};

}  // namespace

void spherical_harmonics(int n_max, double cos_theta, double phi, std::complex<double>* out) {
  thread_local RecurrenceTable table;
  table.reserve(n_max);
  const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  // Fully normalized associated Legendre functions P~_n^m (with the Condon-Shortley phase), by the
  // standard three-term recurrence in n at fixed m, seeded from the sectoral P~_m^m; e^{im phi} by
  // repeated rotation.
  const std::complex<double> rotation = std::polar(1.0, phi);
  std::complex<double> e = 1.0;
  double pmm = std::sqrt(1 / (4 * std::numbers::pi));
  for (int m = 0; m <= n_max; ++m) {
    if (m > 0) {
      pmm *= -std::sqrt((2.0 * m + 1) / (2.0 * m)) * sin_theta;
      e *= rotation;
    }
    double p_prev = 0, p = pmm;
    for (int n = m; n <= n_max; ++n) {
      if (n == m + 1) {
        p_prev = pmm;
        p = std::sqrt(2.0 * m + 3) * cos_theta * pmm;
      } else if (n > m + 1) {
        const auto at = static_cast<std::size_t>(harmonic_index(n, m));
        const double next = table.a[at] * (cos_theta * p - table.b[at] * p_prev);
        p_prev = p;
        p = next;
      }
      const std::complex<double> y = p * e;
      out[harmonic_index(n, m)] = y;
      if (m > 0) out[harmonic_index(n, -m)] = (m % 2 ? -1.0 : 1.0) * std::conj(y);
    }
  }
}

}  // namespace clatter::kernels::transfer
