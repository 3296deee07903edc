#include "kernels/pulse.hpp"

#include <cmath>
#include <numbers>

namespace clatter::kernels {

double pulse(double t_s, double h_s) {
  const double a = std::abs(t_s) / h_s;
  if (a >= 2.0) return 0.0;
  const double y = 1.0 - a;
  if (a <= 1.0) return (((-15.0 * y + 18.0) * y + 9.0) * y + 2.0) / 18.0;
  const double u = 1.0 + y;  // = 2 - a, in [0, 1]
  return u * u * (5.0 * u - 3.0) / 18.0;
}

double monopole_pressure(double r_m, double t_s, double h_s, double c_m_s, double rho_kg_m3) {
  return rho_kg_m3 * pulse(t_s - r_m / c_m_s, h_s) / (4.0 * std::numbers::pi * r_m);
}

}  // namespace clatter::kernels
