#include "tests/reference/ellipsoid_added_mass.hpp"

#include <gsl/gsl_mode.h>
#include <gsl/gsl_sf_ellint.h>

#include <array>
#include <numbers>
#include <stdexcept>

namespace clatter::reference {

double ellipsoid_translation_dipole_m3(double a_m, double b_m, double c_m, int axis) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("ellipsoid_translation_dipole_m3: axis must be 0, 1 or 2");
  const std::array<double, 3> s{a_m, b_m, c_m};
  const double along = s[static_cast<std::size_t>(axis)];
  const double t = s[static_cast<std::size_t>((axis + 1) % 3)], u = s[static_cast<std::size_t>((axis + 2) % 3)];
  const double alpha = 2.0 / 3.0 * a_m * b_m * c_m * gsl_sf_ellint_RD(t * t, u * u, along * along, GSL_PREC_DOUBLE);
  const double volume = 4.0 / 3.0 * std::numbers::pi * a_m * b_m * c_m;
  return 2.0 * volume / (2.0 - alpha);
}

}  // namespace clatter::reference
