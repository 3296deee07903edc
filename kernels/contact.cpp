#include "kernels/contact.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace clatter::kernels {

double hertz_contact_time_s(double m, double r, const model::Material& a, const model::Material& b, double v) {
  if (!(m > 0) || !(r > 0) || !(v > 0) || !(a.youngs_pa > 0) || !(b.youngs_pa > 0))
    throw std::invalid_argument("hertz_contact_time_s: mass, radius, speed and moduli must be > 0");
  const double inv_e = (1 - a.poisson * a.poisson) / a.youngs_pa + (1 - b.poisson * b.poisson) / b.youngs_pa;
  const double e = 1 / inv_e;
  return 2.868 * std::pow(m * m / (r * e * e * v), 0.2);
}

double half_sine(double t, double t0, double tau) {
  if (t < t0 || t > t0 + tau) return 0.0;
  return std::sin(std::numbers::pi * (t - t0) / tau);
}

}  // namespace clatter::kernels
