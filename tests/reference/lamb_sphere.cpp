#include "tests/reference/lamb_sphere.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_bessel.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::reference {
namespace {

// j_n(z) by GSL, with its error code turned into an exception rather than GSL's abort.
double jn(int n, double z) {
  gsl_set_error_handler_off();
  gsl_sf_result r;
  const int status = gsl_sf_bessel_jl_e(n, z, &r);
  if (status != GSL_SUCCESS && status != GSL_EUNDRFLW)
    throw std::runtime_error("gsl_sf_bessel_jl(" + std::to_string(n) + ", " + std::to_string(z) +
                             "): " + gsl_strerror(status));
  return r.val;
}

// z j_n'(z) = n j_n(z) - z j_{n+1}(z): the recurrence, valid for every n >= 0.
double z_djn(int n, double z) { return n * jn(n, z) - z * jn(n + 1, z); }

void check_nu(double nu) {
  if (!(nu >= 0 && nu < 0.5))
    throw std::invalid_argument("lamb: Poisson ratio " + std::to_string(nu) + " not in [0, 1/2)");
}

double torsional_adapter(int n, double y, double) { return lamb_torsional(n, y); }

}  // namespace

double lamb_speed_ratio(double nu) {
  check_nu(nu);
  return std::sqrt(2 * (1 - nu) / (1 - 2 * nu));
}

double lamb_torsional(int n, double y) { return (n - 1) * jn(n, y) - y * jn(n + 1, y); }

double lamb_spheroidal_determinant(int n, double y, double nu) {
  const double x = y / lamb_speed_ratio(nu), l = n * (n + 1.0);
  // a^2 sigma_rr / mu and a^2 sigma_r(theta) / mu per unit P (column 1) and S (column 2) potential.
  const double a11 = (2 * l - y * y) * jn(n, x) - 4 * z_djn(n, x);
  if (n == 0) return a11;
  const double a12 = 2 * l * (z_djn(n, y) - jn(n, y));
  const double a21 = 2 * (z_djn(n, x) - jn(n, x));
  const double a22 = (2 * l - 2 - y * y) * jn(n, y) - 2 * z_djn(n, y);
  return a11 * a22 - a12 * a21;
}

double lamb_spheroidal_saviot(int n, double y, double nu) {
  if (n < 1) throw std::invalid_argument("lamb_spheroidal_saviot: n >= 1 only");
  const double x = y / lamb_speed_ratio(nu), y2 = y * y;
  const double jx = jn(n, x), jx1 = jn(n + 1, x), jy = jn(n, y), jy1 = jn(n + 1, y);
  const double m = (n - 1.0) * (n + 2.0);
  return 2 * (y2 * jy + m * (y * jy1 - (n + 1) * jy)) * x * jx1 +
         (-y2 * y2 / 2 + (n - 1.0) * (2 * n + 1) * y2) * jx * jy + (y2 - 2 * n * m) * y * jy1 * jx;
}

std::vector<double> lamb_roots(double (*f)(int, double, double), int n, double nu, double y_min, double y_max,
                               double step) {
  std::vector<double> roots;
  double lo = y_min, f_lo = f(n, lo, nu);
  for (int i = 1; lo < y_max; ++i) {
    const double hi = std::min(y_min + i * step, y_max), f_hi = f(n, hi, nu);
    if (f_hi == 0) {
      roots.push_back(hi);
    } else if (f_lo != 0 && (f_lo < 0) != (f_hi < 0)) {
      double a = lo, b = hi, f_a = f_lo;
      while (b - a > 1e-14 * b) {
        const double mid = 0.5 * (a + b), f_mid = f(n, mid, nu);
        if (f_mid == 0) {
          a = b = mid;
        } else if ((f_mid < 0) == (f_a < 0)) {
          a = mid;
          f_a = f_mid;
        } else {
          b = mid;
        }
      }
      roots.push_back(0.5 * (a + b));
    }
    lo = hi;
    f_lo = f_hi;
  }
  return roots;
}

std::vector<LambMode> lamb_sphere_modes(double nu, double y_max, double step) {
  check_nu(nu);
  // The lowest root of degree n is above 0.8 n for both families (about the Rayleigh speed times
  // n + 1/2, and above n for the torsional), so degrees beyond 1.3 y_max + 2 add nothing.
  const int n_max = static_cast<int>(1.3 * y_max) + 2;
  // Below y = 0.05 the n = 1 determinant is all cancellation (it vanishes at 0: the translation).
  const double y_min = 0.05;
  std::vector<LambMode> modes;
  for (int n = 0; n <= n_max; ++n) {
    auto add = [&](LambFamily family, const std::vector<double>& roots) {
      for (std::size_t k = 0; k < roots.size(); ++k)
        modes.push_back({family, n, static_cast<int>(k), 2 * n + 1, roots[k]});
    };
    if (n >= 1) add(LambFamily::torsional, lamb_roots(torsional_adapter, n, nu, y_min, y_max, step));
    add(LambFamily::spheroidal, lamb_roots(lamb_spheroidal_determinant, n, nu, y_min, y_max, step));
  }
  std::sort(modes.begin(), modes.end(),
            [](const LambMode& a, const LambMode& b) { return a.omega_a_over_cs < b.omega_a_over_cs; });
  return modes;
}

double lamb_frequency_hz(const LambMode& mode, double radius_m, double youngs_modulus_pa, double nu, double rho_kg_m3) {
  const double c_s_m_s = std::sqrt(youngs_modulus_pa / (2 * (1 + nu) * rho_kg_m3));
  return mode.omega_a_over_cs * c_s_m_s / (2 * std::numbers::pi * radius_m);
}

}  // namespace clatter::reference
