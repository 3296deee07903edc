#include "kernels/ground/lamb.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::kernels::ground {
namespace {

using cplx = std::complex<double>;
constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

void check_nu(double nu, const char* who) {
  if (!(nu > 0 && nu < 0.5))
    throw std::invalid_argument(std::string(who) + ": Poisson's ratio must lie in (0, 0.5), not " + num(nu));
}

// The Rayleigh cubic Q(y) = q3 y^3 + q2 y^2 + q1 y + 1 and its roots: the Rayleigh root y_R > 1
// (Q(1) = 1 > 0, Q -> -inf), by bisection then Newton, and the two others from the deflated
// quadratic, each polished by Newton on Q itself so that all three carry round-off error only.
struct Cubic {
  double q3, q2, q1;
  cplx value(cplx y) const { return ((q3 * y + q2) * y + q1) * y + 1.0; }
  cplx slope(cplx y) const { return (3.0 * q3 * y + 2.0 * q2) * y + q1; }
  cplx polish(cplx y) const {
    for (int i = 0; i < 4; ++i) {
      const cplx d = slope(y);
      if (std::abs(d) == 0) break;
      y -= value(y) / d;
    }
    return y;
  }
};

// arg(r(s_b) / r(s_a)) summed along the path, refined where r turns or changes size quickly, so
// the logarithm stays on one continuous branch.
template <class R>
double unwrap(const R& r, double sa, cplx ra, double sb, cplx rb, int depth) {
  const cplx q = rb / ra;
  const double turn = std::arg(q), grow = std::log(std::abs(q));
  if ((std::abs(turn) < 0.3 && std::abs(grow) < 0.5) || depth > 48) return turn;
  const double sm = 0.5 * (sa + sb);
  const cplx rm = r(sm);
  return unwrap(r, sa, ra, sm, rm, depth + 1) + unwrap(r, sm, rm, sb, rb, depth + 1);
}

}  // namespace

void check_lamb_ground(const model::Material& ground) {
  const std::string bad = model::check_material(ground);
  if (!bad.empty()) throw std::invalid_argument("ground '" + ground.name + "': " + bad);
  check_nu(ground.poisson, "ground");
}

double pekeris_step(double tau) {
  // Pekeris (1955): nu = 1/4, alpha^2 = 1/3, roots 1/4, (3 -+ sqrt 3)/4 of the Rayleigh cubic.
  const double s3 = std::sqrt(3.0), t2 = tau * tau;
  const double y2 = (3 - s3) / 4, y3 = (3 + s3) / 4, x_r = std::sqrt(y3);
  if (tau <= 1 / s3) return 0;
  if (tau <= 1)
    return (6 - s3 / std::sqrt(t2 - 0.25) + std::sqrt(3 * s3 - 5) / std::sqrt(t2 - y2) - std::sqrt(5 + 3 * s3) / std::sqrt(y3 - t2)) /
           (32 * kPi);
  if (tau < x_r) return (12 - 2 * std::sqrt(5 + 3 * s3) / std::sqrt(y3 - t2)) / (32 * kPi);
  return 3 / (8 * kPi);
}

LambSurface::LambSurface(double nu) : nu_(nu) {
  check_nu(nu, "LambSurface");
  const double a2 = (1 - 2 * nu) / (2 * (1 - nu));
  alpha_ = std::sqrt(a2);
  const Cubic q{-16 * (1 - a2), 8 * (3 - 2 * a2), -8};
  double lo = 1, hi = 2;
  while (q.value(hi).real() > 0) hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) (q.value(0.5 * (lo + hi)).real() > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double y_r = q.polish(0.5 * (lo + hi)).real();
  x_rayleigh_ = std::sqrt(y_r);
  // Q / (y - y_R) = q3 y^2 + b y + c (synthetic division), then the quadratic formula.
  const double b = q.q2 + q.q3 * y_r, c = q.q1 + b * y_r;
  const cplx disc = std::sqrt(cplx(b * b - 4 * q.q3 * c, 0.0));
  const cplx roots[3] = {y_r, q.polish((-b + disc) / (2 * q.q3)), q.polish((-b - disc) / (2 * q.q3))};
  int n = 0;
  for (const cplx& y : roots) {
    const cplx dq = q.slope(y);
    const cplx cp = (1.0 - 2.0 * y) * (1.0 - 2.0 * y) / dq, cs = 4.0 * y * (y - a2) / dq;
    // R ends at the Rayleigh front for the Rayleigh root (a principal value beyond it); the other
    // roots lie off the path (below alpha^2 when real), so their R runs on to infinity.
    const double end = (&y == &roots[0]) ? x_rayleigh_ : kInf;
    terms_[n++] = {cp, y, a2, end};
    terms_[n++] = {cs, y, 1.0, end};
  }
}

double LambSurface::step(double tau) const {
  if (!(tau > alpha_)) return 0;  // before the P front (and any tau <= 0, whose square could pass it)
  cplx sum = 0;
  const double t2 = tau * tau;
  for (const Term& t : terms_) {
    if (!(t2 > t.a)) continue;
    const cplx r = tau < t.tau_end ? std::sqrt((t.root - t.a) / (t.root - t2)) : cplx(0);
    sum += t.coefficient * (1.0 - r);
  }
  return -sum.real() / (2 * kPi);
}

double LambSurface::smoothed(double tau, double eta, int k) const {
  if (!(eta > 0) || k < 0 || k > 3) throw std::invalid_argument("LambSurface::smoothed: needs eta > 0 and 0 <= k <= 3");
  const cplx zeta(tau, eta);
  cplx total = 0;
  for (const Term& t : terms_) {
    const double x0 = std::sqrt(t.a);
    // The step H(x - x0): d^k/dzeta^k int_x0^inf dx / (x - zeta) (for k = 0 less a real constant
    // whose sum over the terms is real: sum_j c_j and sum_j d_j are real).
    cplx c_h;
    const cplx d0 = x0 - zeta;
    if (k == 0) c_h = -std::log(d0);
    else c_h = (k == 3 ? 2.0 : 1.0) / std::pow(d0, k);  // (k - 1)!
    // R(x) = K / V(x), V = sqrt(x^2 - y) continuous along the path, K = V(x0): its Cauchy integral
    // is K h(zeta) L(zeta), h = 1/w, w = sqrt(zeta^2 - y), L = [ln((u - v+)/(u - v-))] over the path,
    // u = (x + V)/sqrt(y), v+- = (zeta +- w)/sqrt(y) (docs/ground.md).
    const cplx y = t.root, sy = std::sqrt(y), w = std::sqrt(zeta * zeta - y);
    auto vee = [&](double x) { return std::sqrt(cplx(x * x, 0.0) - y); };
    const cplx vp = (zeta + w) / sy, vm = (zeta - w) / sy;
    // At the Rayleigh front's end of the path V = 0 exactly; x_R^2 - y_R may round to +-2e-16,
    // whose square root (1e-8) would shift the result by 1e-9.
    auto u_of = [&](double x) { return (x + (x == t.tau_end ? cplx(0) : vee(x))) / sy; };
    const bool infinite = !std::isfinite(t.tau_end);
    const double span = t.tau_end - x0;
    auto x_of = [&](double s) { return infinite ? x0 + s / (1 - s) : x0 + s * span; };
    auto ratio = [&](double s) {
      if (infinite && s >= 1) return cplx(1.0);
      const cplx u = u_of(x_of(s));
      return (u - vp) / (u - vm);
    };
    const cplx r0 = ratio(0), r1 = ratio(1);
    // Start the unwrapping from points that bracket where u passes near v+- (x near Re zeta).
    double turn = 0, s_prev = 0;
    cplx r_prev = r0;
    for (int i = 1; i <= 16; ++i) {
      const double s = i / 16.0;
      const cplx r = ratio(s);
      turn += unwrap(ratio, s_prev, r_prev, s, r, 0);
      s_prev = s;
      r_prev = r;
    }
    const cplx L = cplx(std::log(std::abs(r1 / r0)), turn);
    // Derivatives of ln(u - v) in zeta at an end of the path (none at infinity).
    const cplx w1 = zeta / w, w2 = -y / (w * w * w), w3 = 3.0 * y * zeta / std::pow(w, 5);
    auto dl = [&](double x, int m) -> cplx {
      if (!std::isfinite(x)) return 0;
      const cplx u = u_of(x);
      cplx out = 0;
      for (int sgn = -1; sgn <= 1; sgn += 2) {
        const double sg = sgn;
        const cplx v1 = (1.0 + sg * w1) / sy, v2 = sg * w2 / sy, v3 = sg * w3 / sy;
        const cplx e = u - (sgn > 0 ? vp : vm);
        cplx g;
        if (m == 1) g = -v1 / e;
        else if (m == 2) g = -v2 / e - v1 * v1 / (e * e);
        else g = -v3 / e - 3.0 * v1 * v2 / (e * e) - 2.0 * v1 * v1 * v1 / (e * e * e);
        out += sg * g;  // ln(u - v+) - ln(u - v-)
      }
      return out;
    };
    cplx dL[4] = {L, 0, 0, 0};
    for (int m = 1; m <= k; ++m) dL[m] = dl(t.tau_end, m) - dl(x0, m);
    const cplx h[4] = {1.0 / w, -zeta / std::pow(w, 3), (2.0 * zeta * zeta + y) / std::pow(w, 5),
                       -3.0 * zeta * (2.0 * zeta * zeta + 3.0 * y) / std::pow(w, 7)};
    static constexpr int binom[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
    cplx hl = 0;
    for (int i = 0; i <= k; ++i) hl += double(binom[k][i]) * h[i] * dL[k - i];
    const cplx c_r = vee(x0) * hl;
    total += t.coefficient * (c_h - c_r);
  }
  return -(total.imag()) / (2 * kPi * kPi);
}

RegularizedLamb::RegularizedLamb(const model::Material& ground, double epsilon_m)
    : ground_((check_lamb_ground(ground), ground)), epsilon_m_(epsilon_m), c_s_(ground.shear_speed_m_s()), surface_(ground.poisson) {
  if (!(epsilon_m > 0) || !std::isfinite(epsilon_m))
    throw std::invalid_argument("RegularizedLamb: the regularization length must be positive, not " + num(epsilon_m) + " m");
}

double RegularizedLamb::acceleration(double r, double t) const {
  const double tau = c_s_ * t / r, eta = epsilon_m_ / r;
  return -std::pow(c_s_, 3) / (ground_.shear_modulus_pa() * std::pow(r, 4)) * surface_.regularized(tau, eta, 3);
}

double RegularizedLamb::displacement(double r, double t) const {
  const double tau = c_s_ * t / r, eta = epsilon_m_ / r;
  return c_s_ / (ground_.shear_modulus_pa() * r * r) * surface_.regularized(tau, eta, 1);
}

}  // namespace clatter::kernels::ground
