#include "kernels/contact.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace clatter::kernels {

double hertz_contact_time_s(double m, double r, const ElasticMaterial& a, const ElasticMaterial& b, double v) {
  if (!(m > 0) || !(r > 0) || !(v > 0) || !(a.youngs_modulus_pa > 0) || !(b.youngs_modulus_pa > 0))
    throw std::invalid_argument("hertz_contact_time_s: mass, radius, speed and moduli must be > 0");
  const double inv_e = (1 - a.poisson_ratio * a.poisson_ratio) / a.youngs_modulus_pa +
                       (1 - b.poisson_ratio * b.poisson_ratio) / b.youngs_modulus_pa;
  const double e = 1 / inv_e;
  return 2.868 * std::pow(m * m / (r * e * e * v), 0.2);
}

double half_sine(double t, double t0, double tau) {
  if (t < t0 || t > t0 + tau) return 0.0;
  return std::sin(std::numbers::pi * (t - t0) / tau);
}

}  // namespace clatter::kernels
