#include "tests/reference/bar_modes.hpp"

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::reference {
namespace {

constexpr double kPi = std::numbers::pi;

void check_bar(const Bar& b) {
  if (!(b.length_m > 0 && b.width_m > 0 && b.depth_m > 0 && b.youngs_pa > 0 && b.rho_kg_m3 > 0 && b.poisson > -1 && b.poisson < 0.5))
    throw std::invalid_argument("bar: lengths, E and rho must be > 0 and -1 < nu < 0.5");
}

double det4(std::array<std::array<double, 4>, 4> m) {
  // Gaussian elimination with partial pivoting: the rows' scales differ by cosh(alpha L).
  double det = 1;
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    if (m[p][c] == 0) return 0;
    if (p != c) std::swap(m[p], m[c]), det = -det;
    det *= m[c][c];
    for (int r = c + 1; r < 4; ++r) {
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
    }
  }
  return det;
}

// The m-th sign change of f on (lo, ...) in steps of `step`, bisected; `limit` bounds the search.
double nth_root(const std::function<double(double)>& f, int m, double lo, double step, double limit) {
  if (m < 1) throw std::invalid_argument("mode numbers start at 1");
  double a = lo, fa = f(a);
  for (int found = 0; a < limit; a += step) {
    const double b = std::min(a + step, limit), fb = f(b);
    if ((fa < 0) != (fb < 0) && ++found == m) {
      double x = a, y = b, fx = fa;
      for (int i = 0; i < 200 && y - x > 1e-15 * y; ++i) {
        const double mid = 0.5 * (x + y), fm = f(mid);
        ((fm < 0) == (fx < 0) ? x : y) = mid;
        if ((fm < 0) == (fx < 0)) fx = fm;
      }
      return 0.5 * (x + y);
    }
    fa = fb;
  }
  throw std::runtime_error("no root " + std::to_string(m) + " below the search limit " + std::to_string(limit));
}

}  // namespace

double cowper_shear_coefficient_rectangle(double poisson) { return 10 * (1 + poisson) / (12 + 11 * poisson); }

double free_free_beta_l(int mode) {
  // cos x cosh x - 1 changes sign once between consecutive roots; its roots lie near (m + 1/2) pi.
  const double x0 = (mode + 0.5) * kPi;
  return nth_root([](double x) { return std::cos(x) - 1 / std::cosh(x); }, 1, x0 - 1, 1e-3, x0 + 1);
}

double euler_bernoulli_free_free_bending_hz(const Bar& b, int mode) {
  check_bar(b);
  const double area_m2 = b.width_m * b.depth_m, i_m4 = b.width_m * std::pow(b.depth_m, 3) / 12;
  const double bl = free_free_beta_l(mode);
  return bl * bl / (2 * kPi * b.length_m * b.length_m) * std::sqrt(b.youngs_pa * i_m4 / (b.rho_kg_m3 * area_m2));
}

// Harmonic motion w, psi ~ e^{lambda x}: kGA (w'' - psi') + rho A omega^2 w = 0 and
// E I psi'' + kGA (w' - psi) + rho I omega^2 psi = 0 give psi = (lambda + a / lambda) w with
// a = rho omega^2 / (k G), and mu = lambda^2 solves mu^2 + p mu + q = 0, p = rho omega^2 (1/kG + 1/E),
// q = rho^2 omega^4 / (k G E) - rho A omega^2 / (E I). Below the cutoff q < 0: mu = alpha^2 > 0 and
// mu = -beta^2 < 0, and the real solutions are w = cosh, sinh (alpha x), cos, sin (beta x) with
// psi = A sinh, A cosh (A = alpha + a/alpha), -B sin, B cos (B = beta - a/beta). Free ends:
// psi' = 0 (no moment) and w' - psi = 0 (no shear force) at x = 0 and L; everything in units of L,
// and the shear rows divided by a (> 0), so the entries stay of order cosh(alpha L).
double timoshenko_free_free_determinant(const Bar& b, double omega_rad_s) {
  check_bar(b);
  const double shear_pa = b.youngs_pa / (2 * (1 + b.poisson)), kg = cowper_shear_coefficient_rectangle(b.poisson) * shear_pa;
  const double l = b.length_m, area_m2 = b.width_m * b.depth_m, i_m4 = b.width_m * std::pow(b.depth_m, 3) / 12;
  const double rw2 = b.rho_kg_m3 * omega_rad_s * omega_rad_s;
  const double p = rw2 * (1 / kg + 1 / b.youngs_pa) * l * l;
  const double q = (rw2 * rw2 / (kg * b.youngs_pa) - rw2 * area_m2 / (b.youngs_pa * i_m4)) * std::pow(l, 4);
  if (!(q < 0)) throw std::runtime_error("timoshenko: omega above the second spectrum's cutoff");
  const double root = std::sqrt(p * p - 4 * q);
  const double al = std::sqrt((root - p) / 2), bl = std::sqrt((root + p) / 2), a = rw2 / kg * l * l;
  const double ca = al * al + a, cb = bl * bl - a;  // A alpha L^2, B beta L^2
  const double ch = std::cosh(al), sh = std::sinh(al), c = std::cos(bl), s = std::sin(bl);
  return det4({{{ca, 0, -cb, 0},
                {0, -1 / al, 0, 1 / bl},
                {ca * ch, ca * sh, -cb * c, -cb * s},
                {-sh / al, -ch / al, -s / bl, c / bl}}});
}

double timoshenko_free_free_bending_hz(const Bar& b, int mode) {
  const double omega_eb = 2 * kPi * euler_bernoulli_free_free_bending_hz(b, 1);
  const double shear_pa = b.youngs_pa / (2 * (1 + b.poisson)), kg = cowper_shear_coefficient_rectangle(b.poisson) * shear_pa;
  const double cutoff = std::sqrt(kg * 12 / (b.rho_kg_m3 * b.depth_m * b.depth_m));  // sqrt(k G A / (rho I))
  // Rigid motions make the determinant vanish at omega = 0: start the scan clear of it.
  const double omega = nth_root([&](double w) { return timoshenko_free_free_determinant(b, w); }, mode, 0.05 * omega_eb,
                                2e-3 * omega_eb, 0.999 * cutoff);
  return omega / (2 * kPi);
}

double rectangle_torsion_constant_m4(double side_a_m, double side_b_m) {
  if (!(side_a_m > 0 && side_b_m > 0)) throw std::invalid_argument("rectangle sides must be > 0");
  const double a = std::max(side_a_m, side_b_m), b = std::min(side_a_m, side_b_m);
  double sum = 0;
  for (int n = 1;; n += 2) {
    const double term = std::tanh(n * kPi * a / (2 * b)) / std::pow(n, 5);
    sum += term;
    if (term < 1e-17 * sum) break;
  }
  return a * b * b * b * (1.0 / 3 - 64 / std::pow(kPi, 5) * (b / a) * sum);
}

double saint_venant_free_free_torsion_hz(const Bar& b, int mode) {
  check_bar(b);
  const double shear_pa = b.youngs_pa / (2 * (1 + b.poisson));
  const double j_m4 = rectangle_torsion_constant_m4(b.width_m, b.depth_m);
  const double ip_m4 = b.width_m * b.depth_m * (b.width_m * b.width_m + b.depth_m * b.depth_m) / 12;
  return mode / (2 * b.length_m) * std::sqrt(shear_pa * j_m4 / (b.rho_kg_m3 * ip_m4));
}

}  // namespace clatter::reference
