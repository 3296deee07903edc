// The transfer's special functions (kernels/transfer/special_functions.hpp) against GSL, the
// Wronskian, the sum rule's consequences and large-order / large-argument asymptotics, and the
// monopole's multipole expansion (kernels/transfer/multipole.hpp) against the direct sum.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sf_bessel.h>
#include <gsl/gsl_sf_legendre.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <vector>
#include <numbers>

#include "kernels/transfer/multipole.hpp"
#include "kernels/transfer/special_functions.hpp"

namespace {
using namespace clatter::kernels::transfer;
constexpr double kPi = std::numbers::pi;

// sin_cos (the Green's functions' fast path) against libm: log-uniform |x| from 1e-8 to 1e5, both
// signs, and next to the multiples of pi / 2 where the quadrant changes; beyond 1e5 it is libm.
TEST(SinCos, AgreesWithLibm) {
  std::vector<double> xs;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::pow(10.0, -8 + 13.0 * (i + 0.5) / 200000);
    xs.push_back(x);
    xs.push_back(-x);
  }
  for (int n = -1000; n <= 1000; ++n)
    for (const double d : {-1e-12, 0.0, 1e-12}) xs.push_back(n * std::numbers::pi / 2 + d);
  double worst = 0;
  for (const double x : xs) {
    double s = 0, c = 0;
    sin_cos(x, s, c);
    worst = std::max({worst, std::abs(s - std::sin(x)), std::abs(c - std::cos(x))});
  }
  EXPECT_LT(worst, 4e-16);
  double s = 0, c = 0;
  sin_cos(3e5, s, c);
  EXPECT_EQ(s, std::sin(3e5));
  EXPECT_EQ(c, std::cos(3e5));
  std::printf("sin_cos against libm over %zu points: worst absolute difference %.2e\n", xs.size(), worst);
}

TEST(SphericalBessel, AgreesWithGsl) {
  gsl_set_error_handler_off();
  for (double x : {0.05, 0.5, 3.0, 17.3, 68.0, 150.0}) {
    const int n_max = 120;
    const auto j = spherical_bessel_j(n_max, x);
    const auto y = spherical_bessel_y(n_max, x);
    for (int n = 0; n <= n_max; ++n) {
      gsl_sf_result r;
      if (gsl_sf_bessel_jl_e(n, x, &r) == GSL_SUCCESS && std::abs(r.val) > 1e-280) {
        EXPECT_NEAR(j[static_cast<std::size_t>(n)], r.val, 1e-11 * std::abs(r.val) + 1e-14 / x) << "j_" << n << "(" << x << ")";
      }
      if (gsl_sf_bessel_yl_e(n, x, &r) == GSL_SUCCESS && std::isfinite(r.val) && std::abs(r.val) < 1e280) {
        EXPECT_NEAR(y[static_cast<std::size_t>(n)], r.val, 1e-11 * std::abs(r.val)) << "y_" << n << "(" << x << ")";
      }
    }
  }
}

TEST(SphericalBessel, UpwardHankelKeepsItsRelativeAccuracy) {
  // h_n^(2) by the plain upward recurrence (the synthesizer's transfer at a listener) against
  // j_n - i y_n of the checked recurrences, below and far above n = x: relative 1e-12.
  for (double x : {0.2, 3.0, 40.0, 350.0}) {
    const int n_max = 90;
    const auto h = spherical_hankel2(n_max, x);
    std::vector<std::complex<double>> up(static_cast<std::size_t>(n_max) + 1);
    spherical_hankel2_upward(n_max, x, up.data());
    for (std::size_t n = 0; n < h.size(); ++n) {
      if (!std::isfinite(std::abs(h[n]))) break;
      EXPECT_LE(std::abs(up[n] - h[n]), 1e-12 * std::abs(h[n])) << "h_" << n << "(" << x << ")";
    }
  }
}

TEST(SphericalBessel, WronskianHolds) {
  // j_n y_{n-1} - j_{n-1} y_n = 1 / x^2 for every n: ties the two recurrences to each other.
  for (double x : {0.3, 2.0, 25.0, 90.0, 300.0}) {
    const int n_max = static_cast<int>(x) + 40;
    const auto j = spherical_bessel_j(n_max, x);
    const auto y = spherical_bessel_y(n_max, x);
    for (int n = 1; n <= n_max; ++n) {
      const auto u = static_cast<std::size_t>(n);
      const double w = j[u] * y[u - 1] - j[u - 1] * y[u];
      if (!std::isfinite(y[u])) break;
      EXPECT_NEAR(w * x * x, 1.0, 1e-9) << "n = " << n << ", x = " << x;
    }
  }
}

TEST(SphericalBessel, LargeOrderAndLargeArgumentAsymptotics) {
  // n >> x: j_n(x) = x^n / (2n + 1)!! (1 - z / (2n + 3) + z^2 / (2 (2n + 3)(2n + 5)) - ...), z = x^2 / 2.
  for (int n : {100, 150}) {
    const double x = 1.5, z = x * x / 2;
    const double log_dfact = std::lgamma(2.0 * n + 2) - n * std::log(2.0) - std::lgamma(n + 1.0);
    const double expected =
        std::exp(n * std::log(x) - log_dfact) * (1 - z / (2.0 * n + 3) + z * z / (2 * (2.0 * n + 3) * (2.0 * n + 5)));
    const double got = spherical_bessel_j(n, x)[static_cast<std::size_t>(n)];
    EXPECT_NEAR(got / expected, 1.0, 1e-6) << n;
  }
  // x >> n: x h_n^(2)(x) = i^(n+1) e^{-ix} (1 + O(n^2 / x)).
  const double x = 2e4;
  const auto h = spherical_hankel2(6, x);
  for (int n = 0; n <= 6; ++n) {
    const std::complex<double> lead = std::pow(std::complex<double>(0, 1), n + 1) * std::polar(1.0, -x) / x;
    EXPECT_LT(std::abs(h[static_cast<std::size_t>(n)] - lead) / std::abs(lead), 1.0 * n * (n + 1) / (2 * x) + 1e-9) << n;
  }
}

TEST(SphericalHarmonics, AgreeWithGslAndAreOrthonormal) {
  const int n_max = 60;
  std::vector<std::complex<double>> y(static_cast<std::size_t>(harmonic_count(n_max)));
  std::vector<double> gsl(gsl_sf_legendre_array_n(n_max));
  for (double c : {-0.97, -0.3, 0.0, 0.41, 0.999}) {
    spherical_harmonics(n_max, c, 0.0, y.data());
    gsl_sf_legendre_array_e(GSL_SF_LEGENDRE_SPHARM, n_max, c, -1, gsl.data());
    for (int n = 0; n <= n_max; ++n)
      for (int m = 0; m <= n; ++m)
        EXPECT_NEAR(y[static_cast<std::size_t>(harmonic_index(n, m))].real(), gsl[gsl_sf_legendre_array_index(n, m)], 1e-12)
            << n << "," << m;
  }
  // Gauss-Legendre x trapezoid quadrature, exact for degree <= 2 n_max: <Y_n^m, Y_n'^m'> = delta.
  const int q = 20, nq = 2 * q + 1;
  std::vector<double> xs(q), ws(q);
  gsl_integration_glfixed_table* t = gsl_integration_glfixed_table_alloc(q);
  for (int i = 0; i < q; ++i) gsl_integration_glfixed_point(-1, 1, static_cast<std::size_t>(i), &xs[static_cast<std::size_t>(i)], &ws[static_cast<std::size_t>(i)], t);
  gsl_integration_glfixed_table_free(t);
  const int N = 12, count = harmonic_count(N);
  std::vector<std::complex<double>> gram(static_cast<std::size_t>(count * count)), yy(static_cast<std::size_t>(count));
  for (int i = 0; i < q; ++i)
    for (int k = 0; k < nq; ++k) {
      spherical_harmonics(N, xs[static_cast<std::size_t>(i)], 2 * kPi * k / nq, yy.data());
      for (int a = 0; a < count; ++a)
        for (int b = 0; b < count; ++b)
          gram[static_cast<std::size_t>(a * count + b)] += ws[static_cast<std::size_t>(i)] * 2 * kPi / nq * yy[static_cast<std::size_t>(a)] * std::conj(yy[static_cast<std::size_t>(b)]);
    }
  for (int a = 0; a < count; ++a)
    for (int b = 0; b < count; ++b) EXPECT_NEAR(std::abs(gram[static_cast<std::size_t>(a * count + b)] - (a == b ? 1.0 : 0.0)), 0.0, 1e-12);
}

TEST(SphericalHarmonics, LargeOrderAsymptotics) {
  // P_n(cos t) = sqrt(2 / (pi n sin t)) cos((n + 1/2) t - pi / 4) + O(n^-3/2) (Laplace).
  const int n = 2000;
  std::vector<std::complex<double>> y(static_cast<std::size_t>(harmonic_count(n)));
  for (double t : {0.7, 1.3, 2.2}) {
    spherical_harmonics(n, std::cos(t), 0.0, y.data());
    const double p = y[static_cast<std::size_t>(harmonic_index(n, 0))].real() / std::sqrt((2.0 * n + 1) / (4 * kPi));
    const double amplitude = std::sqrt(2 / (kPi * n * std::sin(t)));
    EXPECT_NEAR(p, amplitude * std::cos((n + 0.5) * t - kPi / 4), 2.0 / n * amplitude) << t;
  }
}

TEST(Multipole, MonopoleExpansionMatchesTheDirectField) {
  const Eigen::Vector3d y(0.21, -0.13, 0.34);
  for (double k : {0.5, 8.0, 40.0}) {
    const int order = source_order(k, y.norm());
    Multipole m{k, order, std::vector<std::complex<double>>(static_cast<std::size_t>(harmonic_count(order)))};
    const std::complex<double> strength(0.7, -1.1);
    add_monopole(k, order, y, strength, m.coefficients);
    // At |x| >= 2 |y| (the bank's stated range, r >= 2c), and far.
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(1.0, 0.2, -0.3), Eigen::Vector3d(-0.1, 0.05, 0.9), Eigen::Vector3d(3, 4, 5)}) {
      const double r = (x - y).norm();
      const std::complex<double> direct = strength * std::polar(1 / (4 * kPi * r), -k * r);
      EXPECT_LT(std::abs(m.pressure(x) - direct) / std::abs(direct), 2e-6) << "k " << k;
    }
    // gamma^(-5/2): the same body scaled by 2 (k / 2, strengths of a dp/dn-driven fit) at 2x.
    const Multipole s = scaled(m, 2.0);
    EXPECT_NEAR(std::abs(s.pressure(2 * Eigen::Vector3d(1, 1, 1)) / m.pressure(Eigen::Vector3d(1, 1, 1))), std::pow(2.0, -2.5), 1e-12);
  }
}

TEST(Multipole, MirroredMonopolesInClosedFormEqualTheEightImages) {
  const Eigen::Vector3d y(0.21, 0.13, 0.34);
  const double k = 12.0;
  const int order = source_order(k, y.norm());
  for (int sigma = 0; sigma < 8; ++sigma) {
    std::vector<std::complex<double>> direct(static_cast<std::size_t>(harmonic_count(order))), closed = direct;
    const std::complex<double> strength(0.3, 0.9);
    for (int s = 0; s < 8; ++s) {
      const Eigen::Vector3d image((s & 1) ? -y.x() : y.x(), (s & 2) ? -y.y() : y.y(), (s & 4) ? -y.z() : y.z());
      const double sign = __builtin_popcount(static_cast<unsigned>(s & sigma)) % 2 ? -1.0 : 1.0;
      add_monopole(k, order, image, sign * strength, direct);
    }
    add_mirrored_monopole(k, order, y, std::span(&strength, 1), std::span(&sigma, 1), closed);
    double diff = 0, norm = 0;
    for (std::size_t i = 0; i < direct.size(); ++i) {
      diff += std::norm(direct[i] - closed[i]);
      norm += std::norm(direct[i]);
    }
    EXPECT_LT(std::sqrt(diff / norm), 1e-13) << "class " << sigma;
  }
}

// Several classes of one position in one call (as the transfer's expansion adds them) against
// the 8 images of every class summed one monopole at a time.
TEST(Multipole, MirroredMonopolesOfSeveralClassesAtOnceEqualTheirImages) {
  const Eigen::Vector3d y(0.05, 0.41, 0.17);
  const double k = 9.0;
  const int order = source_order(k, y.norm());
  const std::vector<int> sigmas{0, 3, 5, 6, 7};
  std::vector<std::complex<double>> strengths;
  std::vector<std::complex<double>> direct(static_cast<std::size_t>(harmonic_count(order))), closed = direct;
  for (const int sigma : sigmas) {
    strengths.emplace_back(0.2 + 0.1 * sigma, 1.0 - 0.13 * sigma);
    for (int s = 0; s < 8; ++s) {
      const Eigen::Vector3d image((s & 1) ? -y.x() : y.x(), (s & 2) ? -y.y() : y.y(), (s & 4) ? -y.z() : y.z());
      const double sign = __builtin_popcount(static_cast<unsigned>(s & sigma)) % 2 ? -1.0 : 1.0;
      add_monopole(k, order, image, sign * strengths.back(), direct);
    }
  }
  add_mirrored_monopole(k, order, y, strengths, sigmas, closed);
  double diff = 0, norm = 0;
  for (std::size_t i = 0; i < direct.size(); ++i) {
    diff += std::norm(direct[i] - closed[i]);
    norm += std::norm(direct[i]);
  }
  EXPECT_LT(std::sqrt(diff / norm), 1e-13);
}

}  // namespace
