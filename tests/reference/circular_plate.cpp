#include "tests/reference/circular_plate.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_bessel.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::reference {
namespace {

double bessel_j(int n, double x) {
  gsl_sf_result r;
  const int status = gsl_sf_bessel_Jn_e(n, x, &r);
  if (status != GSL_SUCCESS && status != GSL_EUNDRFLW) throw std::runtime_error(std::string("gsl_sf_bessel_Jn: ") + gsl_strerror(status));
  return r.val;
}

double bessel_i(int n, double x) {
  gsl_sf_result r;
  const int status = gsl_sf_bessel_In_e(std::abs(n), x, &r);  // I_{-n} = I_n
  if (status != GSL_SUCCESS && status != GSL_EUNDRFLW) throw std::runtime_error(std::string("gsl_sf_bessel_In: ") + gsl_strerror(status));
  return r.val;
}

}  // namespace

double free_circular_plate_equation(int n, double l, double nu) {
  gsl_set_error_handler_off();
  const double j = bessel_j(n, l), dj = 0.5 * (bessel_j(n - 1, l) - bessel_j(n + 1, l));
  const double i = bessel_i(n, l), di = 0.5 * (bessel_i(n - 1, l) + bessel_i(n + 1, l));
  const double nn = static_cast<double>(n) * n;
  const double moment_j = l * l * j + (1 - nu) * (l * dj - nn * j), moment_i = l * l * i - (1 - nu) * (l * di - nn * i);
  const double shear_j = l * l * l * dj + (1 - nu) * nn * (l * dj - j), shear_i = l * l * l * di - (1 - nu) * nn * (l * di - i);
  return moment_j * shear_i - moment_i * shear_j;
}

std::vector<PlateMode> free_circular_plate_modes(double nu, int count) {
  if (!(nu > -1 && nu < 0.5) || count < 1) throw std::invalid_argument("free_circular_plate_modes: -1 < nu < 0.5, count >= 1");
  std::vector<PlateMode> modes;
  // Every root with lambda below lambda_max, for n until a family's first root lies above it;
  // lambda_max grows until the list holds `count` modes.
  for (double lambda_max = 8;; lambda_max *= 1.5) {
    modes.clear();
    for (int n = 0;; ++n) {
      const std::size_t before = modes.size();
      // lambda = 0 is a root for n = 0, 1 (rigid motions): start the scan clear of it.
      double a = 0.5, fa = free_circular_plate_equation(n, a, nu);
      for (const double step = 1e-3; a < lambda_max; a += step) {
        const double b = a + step, fb = free_circular_plate_equation(n, b, nu);
        if ((fa < 0) != (fb < 0)) {
          double x = a, y = b, fx = fa;
          for (int k = 0; k < 200 && y - x > 1e-15 * y; ++k) {
            const double mid = 0.5 * (x + y), fm = free_circular_plate_equation(n, mid, nu);
            if ((fm < 0) == (fx < 0)) x = mid, fx = fm;
            else y = mid;
          }
          const double l = 0.5 * (x + y);
          const int s = static_cast<int>(modes.size() - before) + (n <= 1 ? 1 : 0);
          modes.push_back({n, s, l * l});
        }
        fa = fb;
      }
      if (modes.size() == before && n > 1) break;  // higher n start higher still
    }
    if (static_cast<int>(modes.size()) >= count) break;
  }
  std::sort(modes.begin(), modes.end(), [](const PlateMode& x, const PlateMode& y) { return x.lambda2 < y.lambda2; });
  modes.resize(static_cast<std::size_t>(count));
  return modes;
}

double circular_plate_frequency_hz(const PlateMode& mode, double radius_m, double thickness_m, double youngs_pa, double poisson,
                                   double rho_kg_m3) {
  const double d_n_m = youngs_pa * std::pow(thickness_m, 3) / (12 * (1 - poisson * poisson));
  return mode.lambda2 / (2 * std::numbers::pi * radius_m * radius_m) * std::sqrt(d_n_m / (rho_kg_m3 * thickness_m));
}

double mindlin_over_kirchhoff_estimate(double lambda2, double thickness_over_radius, double poisson) {
  const double kt = std::sqrt(lambda2) * thickness_over_radius, kappa2 = std::numbers::pi * std::numbers::pi / 12;
  return 1 - kt * kt / 24 * (1 + 2 / (kappa2 * (1 - poisson)));
}

}  // namespace clatter::reference
