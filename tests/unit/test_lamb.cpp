// Lamb's problem (kernels/ground/lamb.hpp) against references that share none of its algebra:
// Pekeris's explicit nu = 1/4 formula, a Cagniard-de Hoop quadrature of the step response done
// here with GSL on the Rayleigh function itself (not the rationalized cubic), Boussinesq's static
// value, continuity at the fronts, bad input, and the units and impulse balance of RegularizedLamb.
// The regularization's closed form is checked in test_lamb_regularized.cpp.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "kernels/ground/lamb.hpp"
#include "tests/unit/make_material.hpp"

using namespace clatter::kernels::ground;
using clatter::test::ground;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// worst = max(worst, err), except that a NaN err wins (std::max would drop it and pass).
void keep_worst(double& worst, double err) {
  if (!(err <= worst)) worst = err;
}

double front_distance(const LambSurface& s, double tau) {
  return std::min({std::abs(tau - s.alpha()), std::abs(tau - 1), std::abs(tau - s.rayleigh_tau())});
}

// A callable as a gsl_function (GSL only reads through params).
template <class F>
gsl_function as_gsl(const F& f) {
  gsl_function g;
  g.function = [](double x, void* p) { return (*static_cast<const F*>(p))(x); };
  g.params = const_cast<void*>(static_cast<const void*>(&f));
  return g;
}

// GSL's adaptive rules with one workspace; NaN when GSL reports failure, so a bad reference
// fails the comparison instead of passing silently.
class Quadrature {
 public:
  Quadrature() : work_(gsl_integration_workspace_alloc(kLimit)), table_(gsl_integration_qaws_table_alloc(0, -0.5, 0, 0)) {
    gsl_set_error_handler_off();
  }
  ~Quadrature() {
    gsl_integration_qaws_table_free(table_);
    gsl_integration_workspace_free(work_);
  }
  Quadrature(const Quadrature&) = delete;
  Quadrature& operator=(const Quadrature&) = delete;

  template <class F>
  double regular(const F& f, double lo, double hi) const {  // int_lo^hi f
    gsl_function g = as_gsl(f);
    double v, e;
    const int status = gsl_integration_qags(&g, lo, hi, kAbs, kRel, kLimit, work_, &v, &e);
    return ok(status, v, e);
  }
  template <class F>
  double sqrt_end(const F& f, double lo, double hi) const {  // int_lo^hi f(x) (hi - x)^(-1/2)
    gsl_function g = as_gsl(f);
    double v, e;
    const int status = gsl_integration_qaws(&g, lo, hi, table_, kAbs, kRel, kLimit, work_, &v, &e);
    return ok(status, v, e);
  }
  template <class F>
  double cauchy(const F& f, double lo, double hi, double pole) const {  // PV int_lo^hi f(x) / (x - pole)
    gsl_function g = as_gsl(f);
    double v, e;
    const int status = gsl_integration_qawc(&g, lo, hi, pole, kAbs, kRel, kLimit, work_, &v, &e);
    return ok(status, v, e);
  }

 private:
  static constexpr size_t kLimit = 1000;
  static constexpr double kAbs = 1e-15, kRel = 1e-12;
  // GSL_EROUND with a tiny error estimate: the requested 1e-12 meets the ~1e-16 noise of the
  // pole-subtracted integrand near x_R; the result is still good to its estimate.
  static double ok(int status, double v, double err) {
    return status == GSL_SUCCESS || (status == GSL_EROUND && err < 1e-12) ? v : kNaN;
  }
  gsl_integration_workspace* work_;
  gsl_integration_qaws_table* table_;
};

// The Cagniard-de Hoop step response (our derivation, independent of the rationalized cubic):
//   S(tau) = -(1/pi^2) PV int_alpha^tau ImG(x) x / sqrt(tau^2 - x^2) dx,
// with the Rayleigh function DR found here by bisection and its pole removed by its residue.
class CagniardStep {
 public:
  explicit CagniardStep(double nu) : a2_((1 - 2 * nu) / (2 * (1 - nu))), a_(std::sqrt(a2_)) {
    double lo = 1, hi = 1.5;  // DR(1) = 1 > 0, DR(1.5) < 0 for every nu in (0, 0.5)
    for (int i = 0; i < 200 && hi - lo > 4e-16; ++i) (rayleigh(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
    x_r_ = 0.5 * (lo + hi);
    residue_ = std::sqrt(x_r_ * x_r_ - a2_) / rayleigh_slope(x_r_);
  }
  double rayleigh_tau() const { return x_r_; }

  double operator()(double tau) const {
    if (tau <= a_) return 0;
    const Quadrature q;
    auto plain = [&](double x) { return im_g(x) * x / std::sqrt(tau * tau - x * x); };
    auto at_end = [&](double x) { return im_g(x) * x / std::sqrt(tau + x); };  // times (tau - x)^(-1/2)
    if (tau <= 1) return -q.sqrt_end(at_end, a_, tau) / (kPi * kPi);
    double v = q.regular(plain, a_, 1);
    if (tau < x_r_) return -(v + q.sqrt_end(at_end, 1, tau)) / (kPi * kPi);
    // Past the Rayleigh pole: ImG - res/(x - x_R) is regular, and res/(x - x_R) is integrated as a
    // principal value up to the midpoint m, then with the endpoint weight from m to tau.
    auto smooth = [&](double x) { return x == x_r_ ? 0.0 : im_g(x) - residue_ / (x - x_r_); };
    const double m = 0.5 * (x_r_ + tau);
    v += q.regular([&](double x) { return smooth(x) * x / std::sqrt(tau * tau - x * x); }, 1, x_r_);
    v += q.sqrt_end([&](double x) { return smooth(x) * x / std::sqrt(tau + x); }, x_r_, tau);
    v += residue_ * q.cauchy([&](double x) { return x / std::sqrt(tau * tau - x * x); }, 1, m, x_r_);
    v += residue_ * q.sqrt_end([&](double x) { return x / ((x - x_r_) * std::sqrt(tau + x)); }, m, tau);
    return -v / (kPi * kPi);
  }

 private:
  double a2_, a_, x_r_ = 0, residue_ = 0;

  double rayleigh(double x) const {  // DR(x), x > 1
    const double b = 1 - 2 * x * x;
    return b * b - 4 * x * x * std::sqrt(x * x - a2_) * std::sqrt(x * x - 1);
  }
  double rayleigh_slope(double x) const {  // DR'(x), by hand
    const double p = std::sqrt(x * x - a2_), s = std::sqrt(x * x - 1);
    return -8 * x * (1 - 2 * x * x) - 8 * x * p * s - 4 * x * x * x * (s / p + p / s);
  }
  double im_g(double x) const {
    const double p = std::sqrt(x * x - a2_);
    if (x < 1) {
      const double b = (1 - 2 * x * x) * (1 - 2 * x * x), c = 4 * x * x * p * std::sqrt(1 - x * x);
      return p * b / (b * b + c * c);
    }
    return p / rayleigh(x);
  }
};

}  // namespace

TEST(Lamb, PekerisRoundOff) {
  // Two evaluations of the same function (Pekeris's constants vs the cubic's roots found
  // numerically): they may differ by round-off only, amplified near the fronts where S has
  // cancelling O(1) terms or the 1/sqrt singularity; 1e-3 away from them, 1e-12 leaves 100x margin.
  const LambSurface s(0.25);
  double worst = 0;
  int compared = 0;
  for (int i = 1; i < 40000; ++i) {
    const double tau = 4.0 * i / 40000;
    if (front_distance(s, tau) < 1e-3) continue;
    const double ref = pekeris_step(tau), got = s.step(tau);
    if (ref == 0) {
      EXPECT_EQ(got, 0.0) << "tau " << tau;
      continue;
    }
    keep_worst(worst, std::abs(got - ref) / std::abs(ref));
    ++compared;
  }
  std::printf("Lamb: nu = 1/4 against Pekeris on %d taus in (0, 4): worst relative difference %.3g\n", compared, worst);
  EXPECT_LE(worst, 1e-12);
}

TEST(Lamb, CagniardQuadratureMatchesTheClosedForm) {
  // The issue asks for 1e-4; the quadrature is converged to ~1e-12 relative (GSL's estimate), and
  // 0.02 from the fronts the closed form is round-off accurate, so anything above 1e-8 would be a
  // real discrepancy (a wrong root, branch or coefficient moves S by far more).
  for (const double nu : {0.2, 0.25, 0.33, 0.45}) {
    const LambSurface s(nu);
    const CagniardStep ref(nu);
    // The Rayleigh front from the irrational Rayleigh function vs from the cubic's root.
    EXPECT_NEAR(s.rayleigh_tau(), ref.rayleigh_tau(), 1e-13) << "nu " << nu;
    double worst = 0;
    for (int i = 0; i <= 160; ++i) {
      const double tau = s.alpha() + (3.5 - s.alpha()) * i / 160;
      if (front_distance(s, tau) < 0.02) continue;
      const double want = ref(tau), got = s.step(tau);
      keep_worst(worst, std::abs(got - want) / std::abs(want));
    }
    std::printf("Lamb: nu = %g, Cagniard-de Hoop quadrature vs closed form: worst relative error %.3g\n", nu, worst);
    EXPECT_LE(worst, 1e-8) << "nu " << nu;
  }
}

TEST(Lamb, StaticAfterTheRayleighFrontZeroBeforeThePFrontContinuousBetween) {
  // Boussinesq: the static surface displacement under P is P (1 - nu) / (2 pi mu r). After the
  // Rayleigh front the closed form must sum to it exactly (the non-Rayleigh roots cancel), so to
  // round-off: 1e-13. Continuity: S has finite slopes at alpha and 1, so 1e-10 either side of a
  // front the values differ by ~1e-10 x S' of the static value; 1e-6 would catch any jump.
  double worst_static = 0, worst_jump = 0;
  for (const double nu : {0.05, 0.2, 0.25, 0.3, 0.33, 0.4, 0.45, 0.49}) {
    const LambSurface s(nu);
    const double boussinesq = (1 - nu) / (2 * kPi);
    EXPECT_DOUBLE_EQ(s.static_value(), boussinesq);
    for (const double tau : {s.rayleigh_tau() + 1e-9, s.rayleigh_tau() + 1e-3, 1.5, 2.0, 3.7, 10.0, 1e3, 1e6})
      keep_worst(worst_static, std::abs(s.step(tau) - boussinesq) / boussinesq);
    for (const double tau : {-1.0, 0.0, 0.5 * s.alpha(), s.alpha()}) EXPECT_EQ(s.step(tau), 0.0) << "nu " << nu;
    for (const double front : {s.alpha(), 1.0}) {
      const double jump = std::abs(s.step(front + 1e-10) - s.step(front - 1e-10)) / boussinesq;
      EXPECT_LE(jump, 1e-6) << "nu " << nu << " front " << front;
      keep_worst(worst_jump, jump);
    }
    // Just before the Rayleigh front S grows without bound (the one-sided singularity).
    EXPECT_GT(std::abs(s.step(s.rayleigh_tau() - 1e-10)), 100 * boussinesq) << "nu " << nu;
  }
  std::printf("Lamb: static value after the Rayleigh front: worst relative error %.3g; worst jump at alpha or 1: %.3g "
              "of the static value\n", worst_static, worst_jump);
  EXPECT_LE(worst_static, 1e-13);
}

TEST(Lamb, RefusesBadInput) {
  for (const double nu : {0.0, 0.5, -0.1, 0.7, kNaN}) EXPECT_THROW(LambSurface{nu}, std::invalid_argument) << nu;
  auto message = [](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "no std::invalid_argument";
    return std::string();
  };
  // The message names the offending value (printed %.6g).
  EXPECT_NE(message([] { check_lamb_ground(ground(-3.25e9, 0.3, 2000)); }).find("-3.25e+09"), std::string::npos);
  EXPECT_NE(message([] { check_lamb_ground(ground(2e9, 0.625, 2000)); }).find("0.625"), std::string::npos);
  EXPECT_NE(message([] { check_lamb_ground(ground(2e9, -0.125, 2000)); }).find("-0.125"), std::string::npos);
  EXPECT_NE(message([] { check_lamb_ground(ground(2e9, 0.3, -1750)); }).find("-1750"), std::string::npos);
  EXPECT_THROW(check_lamb_ground(ground(0, 0.3, 2000)), std::invalid_argument);
  EXPECT_THROW(check_lamb_ground(ground(std::numeric_limits<double>::infinity(), 0.3, 2000)), std::invalid_argument);
  EXPECT_THROW(check_lamb_ground(ground(kNaN, 0.3, 2000)), std::invalid_argument);
  EXPECT_THROW(check_lamb_ground(ground(2e9, 0.5, 2000)), std::invalid_argument);
  EXPECT_THROW(check_lamb_ground(ground(2e9, 0, 2000)), std::invalid_argument);
  EXPECT_THROW(check_lamb_ground(ground(2e9, 0.3, 0)), std::invalid_argument);
  EXPECT_THROW(check_lamb_ground(ground(2e9, 0.3, kNaN)), std::invalid_argument);
  EXPECT_THROW(RegularizedLamb(ground(2e9, 0, 2000), 0.01), std::invalid_argument);
  const LambSurface s(0.25);
  for (const double eta : {0.0, -0.1, kNaN}) EXPECT_THROW(s.smoothed(1.0, eta, 0), std::invalid_argument) << eta;
  for (const int k : {-1, 4}) EXPECT_THROW(s.smoothed(1.0, 0.1, k), std::invalid_argument) << k;
  const clatter::model::Material g = ground(2e9, 0.3, 2000);
  for (const double eps : {0.0, -0.01, kNaN}) EXPECT_THROW(RegularizedLamb(g, eps), std::invalid_argument) << eps;
  EXPECT_NE(message([&] { RegularizedLamb(g, -0.0375); }).find("-0.0375"), std::string::npos);
}

TEST(Lamb, RegularizedLambUnitsAndImpulseBalance) {
  // Moduli from the definitions, not from the material's accessors.
  const double e_pa = 2e8, nu = 0.3, rho = 1800, eps_m = 0.02, r_m = 0.5;
  const double mu_pa = e_pa / (2 * (1 + nu)), c_s = std::sqrt(mu_pa / rho);
  const clatter::model::Material g = ground(e_pa, nu, rho);
  EXPECT_NEAR(g.shear_modulus_pa(), mu_pa, 1e-15 * mu_pa);
  EXPECT_NEAR(g.shear_speed_m_s(), c_s, 1e-14 * c_s);
  EXPECT_NEAR(g.pressure_speed_m_s(), c_s * std::sqrt((2 - 2 * nu) / (1 - 2 * nu)), 1e-13 * c_s);
  const RegularizedLamb lamb(g, eps_m);
  const LambSurface s(nu);
  // Same formula, evaluated in another order: tau may differ by an ulp, which the steep k = 3
  // kernel (slope ~ 1/eta relative) turns into ~1e-14; 1e-11 is round-off with margin.
  double worst = 0;
  for (const double t_s : {0.5, 0.9, 1.02, 1.1, 1.3, 2.0}) {
    const double t = t_s * r_m / c_s, tau = c_s * t / r_m, eta = eps_m / r_m;
    const double a_want = -std::pow(c_s, 3) / (mu_pa * std::pow(r_m, 4)) * s.regularized(tau, eta, 3);
    const double u_want = c_s / (mu_pa * r_m * r_m) * s.regularized(tau, eta, 1);
    keep_worst(worst, std::abs(lamb.acceleration(r_m, t) - a_want) / std::abs(a_want));
    keep_worst(worst, std::abs(lamb.displacement(r_m, t) - u_want) / std::abs(u_want));
  }
  EXPECT_LE(worst, 1e-11);
  // A unit impulse's displacement integrates over time to the unit step's: Boussinesq's static
  // (1 - nu) / (2 pi mu r). Trapezoid with tau steps of eta/4: the integrand is analytic for
  // |Im tau| < eta, so the rule's error is ~exp(-2 pi eta / h) = exp(-8 pi) ~ 1e-11. From t = 0 the
  // integral misses (f_eta * S)(0), the kernel's 6 eta^3 / (pi x^4) tail ahead of the P front, ~1e-5
  // here: hence 1e-3. From t = -T it misses only the tails beyond +-T, ~(eta/T)^3 ~ 1e-8: 1e-7.
  const double boussinesq = (1 - nu) / (2 * kPi * mu_pa * r_m), big_t = 20 * r_m / c_s, dt = eps_m / (4 * c_s);
  const int n = int(std::ceil(big_t / dt));
  auto trapezoid = [&](int first, int last) {
    double sum = 0;
    for (int i = first; i <= last; ++i) sum += (i == first || i == last ? 0.5 : 1.0) * lamb.displacement(r_m, i * dt);
    return sum * dt;
  };
  const double from_zero = trapezoid(0, n), before = trapezoid(-n, 0);
  const double err_causal = std::abs(from_zero - boussinesq) / boussinesq;
  const double err_all = std::abs(from_zero + before - boussinesq) / boussinesq;
  std::printf("Lamb: impulse displacement integrated over [0, T]: %.3g from Boussinesq; over [-T, T]: %.3g "
              "(units: worst %.3g)\n", err_causal, err_all, worst);
  EXPECT_LE(err_causal, 1e-3);
  EXPECT_LE(err_all, 1e-7);
}
