#include "kernels/ground/rayleigh.hpp"

#include "kernels/fem/tet_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace clatter::kernels::ground {
namespace {

struct Rule {
  std::vector<double> x, w;  // on [0, 1]
};

Rule gauss_legendre(int n) {
  Rule r;
  fem::gauss_legendre_unit(n, r.x, r.w);
  return r;
}

// int_lo^hi f over panels no longer than h.
template <class F>
double composite(const Rule& rule, double lo, double hi, double h, F&& f) {
  if (!(hi > lo)) return 0;
  const int panels = std::max(1, static_cast<int>(std::ceil((hi - lo) / h)));
  const double width = (hi - lo) / panels;
  double sum = 0;
  for (int p = 0; p < panels; ++p) {
    const double start = lo + p * width;
    for (std::size_t i = 0; i < rule.x.size(); ++i) sum += rule.w[i] * f(start + width * rule.x[i]);
  }
  return width * sum;
}

}  // namespace

RayleighPressure rayleigh_pressure(const SurfaceField& field, double rho, double z, double t, const RayleighSettings& s) {
  if (!(z > 0)) throw std::invalid_argument("rayleigh_pressure: the listener must be above the surface (z = " + std::to_string(z) + " m)");
  if (!(rho >= 0)) throw std::invalid_argument("rayleigh_pressure: the horizontal distance must be >= 0 (" + std::to_string(rho) + " m)");
  if (!(s.resolution_m > 0) || s.nodes_per_panel < 1 || !(s.c0_m_s > 0))
    throw std::invalid_argument("rayleigh_pressure: needs resolution_m > 0, nodes_per_panel >= 1, c0 > 0");
  const Rule rule = gauss_legendre(s.nodes_per_panel);
  RayleighPressure out;
  const double c0 = s.c0_m_s;
  auto ring_s = [&](double big_r) { return std::sqrt(std::max(big_r * big_r - z * z, 0.0)); };
  // R_end: the first ring past the disk, s(R) = rho + r_max(t - R/c0); s rises and r_max falls with
  // R, so bisection on [z, c0 t] finds it.
  double end = c0 * t;
  if (!(end > z)) return out;
  auto outside = [&](double big_r) { return ring_s(big_r) > rho + field.support_radius_m(t - big_r / c0); };
  if (outside(end)) {
    double lo = z, hi = end;
    if (outside(lo)) return out;  // the listener's foot is already beyond the field
    for (int i = 0; i < 100 && hi - lo > 1e-15 * hi; ++i) (outside(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    end = hi;
  }
  auto ring = [&](double big_r) {
    const double sr = ring_s(big_r), tau = t - big_r / c0, r_max = field.support_radius_m(tau);
    if (rho == 0 || sr == 0) {
      ++out.evaluations;
      return sr <= r_max ? 2 * std::numbers::pi * field.acceleration(sr, tau) : 0.0;
    }
    // cos psi >= (rho^2 + s^2 - r_max^2) / (2 rho s): the arc of the ring inside the disk.
    const double c = std::isinf(r_max) ? -1.0 : (rho * rho + sr * sr - r_max * r_max) / (2 * rho * sr);
    if (c >= 1) return 0.0;
    const double psi_max = std::acos(std::max(c, -1.0));
    const double arc = composite(rule, 0, psi_max, s.resolution_m / sr, [&](double psi) {
      ++out.evaluations;
      return field.acceleration(std::sqrt(std::max(rho * rho + sr * sr - 2 * rho * sr * std::cos(psi), 0.0)), tau);
    });
    return 2 * arc;
  };
  out.pressure_pa = s.rho0_kg_m3 / (2 * std::numbers::pi) * composite(rule, z, end, s.resolution_m, ring);
  return out;
}

}  // namespace clatter::kernels::ground
