#include "tests/reference/ground_pressure.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <stdexcept>

namespace clatter::reference {
namespace {

using kernels::ground::LambSurface;
constexpr double kPi = std::numbers::pi;

// GSL's adaptive rules on a std::function, each level of nesting with its own workspace.
class Integrator {
 public:
  Integrator() : ws_(gsl_integration_workspace_alloc(kLimit), gsl_integration_workspace_free) { gsl_set_error_handler_off(); }
  // QAGP over the ascending points (ends included); QAG (21-point Kronrod, no extrapolation: the
  // psi integrand has interior logarithmic singularities where rays graze a front) when only two.
  double operator()(const std::function<double(double)>& f, std::vector<double> points, double epsrel, double epsabs) {
    gsl_function g{[](double x, void* p) { return (*static_cast<const std::function<double(double)>*>(p))(x); },
                   const_cast<std::function<double(double)>*>(&f)};
    double result = 0, error = 0;
    int status = 0;
    if (points.size() == 2)
      status = gsl_integration_qag(&g, points[0], points[1], epsabs, epsrel, kLimit, GSL_INTEG_GAUSS21, ws_.get(), &result, &error);
    else
      status = gsl_integration_qagp(&g, points.data(), points.size(), epsabs, epsrel, kLimit, ws_.get(), &result, &error);
    if (status == GSL_ESING || status == GSL_EDIVERGE) {
      // QAGP's extrapolation can stall on a ray that nearly grazes a front (two singular points a
      // hair apart); plain bisection piece by piece converges there.
      result = 0;
      status = GSL_SUCCESS;
      for (std::size_t i = 0; i + 1 < points.size() && status != GSL_EFAILED; ++i) {
        double piece = 0;
        const int s = gsl_integration_qag(&g, points[i], points[i + 1], epsabs, epsrel, kLimit, GSL_INTEG_GAUSS21, ws_.get(), &piece,
                                          &error);
        if (s != GSL_SUCCESS && s != GSL_EROUND && s != GSL_EMAXITER && s != GSL_ESING) status = s;
        result += piece;
      }
    }
    // Roundoff limits near the requested tolerance are expected; anything else is a failed reference.
    if (status != GSL_SUCCESS && status != GSL_EROUND && status != GSL_EMAXITER)
      throw std::runtime_error(std::string("reference quadrature failed: ") + gsl_strerror(status));
    return result;
  }

 private:
  static constexpr std::size_t kLimit = 4000;
  std::unique_ptr<gsl_integration_workspace, void (*)(gsl_integration_workspace*)> ws_;
};

// Sorted, without points closer than 1e-13 relative.
std::vector<double> tidy(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end(), [](double a, double b) { return b - a <= 1e-13 * (1 + std::abs(a)); }), x.end());
  return x;
}

// The minimum of a convex function on [lo, hi] (golden section).
template <class F>
double argmin(const F& f, double lo, double hi) {
  const double k = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * (1 + hi); ++i) {
    const double x1 = hi - k * (hi - lo), x2 = lo + k * (hi - lo);
    if (f(x1) < f(x2)) hi = x2;
    else lo = x1;
  }
  return 0.5 * (lo + hi);
}

// Where g (continuous) changes sign on the samples xs, bisected to 1e-14.
template <class G>
void roots(const G& g, const std::vector<double>& xs, std::vector<double>& out) {
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    double a = xs[i], b = xs[i + 1];
    const double ga = g(a), gb = g(b);
    if (!(ga * gb < 0)) continue;
    for (int it = 0; it < 100 && b - a > 1e-14 * (1 + b); ++it) {
      const double m = 0.5 * (a + b);
      if ((g(m) < 0) == (ga < 0)) a = m;
      else b = m;
    }
    out.push_back(0.5 * (a + b));
  }
}

// 004's kernel's second derivative: f = 2 P_eta - P_2eta, P_a(x) = a / (pi (x^2 + a^2)),
// P_a'' = (2a / pi) (3x^2 - a^2) / (x^2 + a^2)^3.
double f_second(double x, double eta) {
  auto p2 = [x](double a) {
    const double d = x * x + a * a;
    return 2 * a / kPi * (3 * x * x - a * a) / (d * d * d);
  };
  return 2 * p2(eta) - p2(2 * eta);
}

struct Node {
  double s, w;
};

// Gauss-Legendre panels on [a, b], at most h_max long, graded geometrically (factor 2) from
// h_min at both ends.
void panels(double a, double b, double h_min, double h_max, std::vector<double>& edges) {
  std::vector<double> e{a, b};
  for (double x = a, h = h_min; x + h < 0.5 * (a + b); x += h, h = std::min(2 * h, h_max)) e.push_back(x + h);
  for (double x = b, h = h_min; x - h > 0.5 * (a + b); x -= h, h = std::min(2 * h, h_max)) e.push_back(x - h);
  e = tidy(e);
  // Split the long middle panels.
  for (std::size_t i = 0; i + 1 < e.size(); ++i) {
    const auto n = static_cast<int>(std::ceil((e[i + 1] - e[i]) / h_max - 1e-9));
    for (int k = 0; k < n; ++k) edges.push_back(e[i] + (e[i + 1] - e[i]) * k / n);
  }
}

}  // namespace

double ground_step_volume(const LambSurface& g, double mach, double elevation_rad, double s) {
  thread_local Integrator outer, inner;
  const double rho = std::cos(elevation_rad), alpha = g.alpha();
  const double fronts[3] = {alpha, 1.0, g.rayleigh_tau()};
  const double r_top = (s + mach) / (alpha + mach);  // past it q < alpha: R >= r - 1
  const bool overhead = rho < 1e-12;
  auto ray = [&](double psi) {
    const double c = rho * std::cos(psi);
    auto big_r = [&](double r) { return std::sqrt(std::max(r * r - 2 * r * c + 1, 0.0)); };
    auto q = [&](double r) { return (s - mach * big_r(r)) / r; };
    std::vector<double> xs;
    for (int i = 1; i <= 256; ++i) xs.push_back(r_top * (i / 256.0) * (i / 256.0));
    std::vector<double> points{0.0, r_top};
    if (s < mach) {  // q rises to one maximum, then falls: with it sampled, each side is monotone
      const double r_star = argmin([&](double r) { return -q(r); }, 0.0, r_top);
      xs.push_back(r_star);
      points.push_back(r_star);
    }
    xs = tidy(xs);
    for (double v : fronts) roots([&](double r) { return q(r) - v; }, xs, points);
    if (c > 0 && c < r_top) points.push_back(c);  // the listener's foot: 1/R peaks
    return inner([&](double r) { return g.step(q(r)) / big_r(r); }, tidy(points), 1e-10, 1e-11);
  };
  if (overhead) return ray(0);
  // Before the direct sound a ray may graze a front (max over r of q equals it): the ray integral
  // has a logarithmic singularity in psi there. max_r q falls as psi grows, so bisection finds each
  // such angle, and QAGP takes them as break points.
  std::vector<double> psi_points{0.0, kPi};
  if (s < mach) {
    auto q_max = [&](double psi) {
      const double c = rho * std::cos(psi);
      auto q = [&](double r) { return (s - mach * std::sqrt(std::max(r * r - 2 * r * c + 1, 0.0))) / r; };
      return q(argmin([&](double r) { return -q(r); }, 0.0, r_top));
    };
    const double at_0 = q_max(0), at_pi = q_max(kPi);
    for (double v : fronts) {
      if (!(at_0 > v && at_pi < v)) continue;
      double a = 0, b = kPi;
      for (int i = 0; i < 60; ++i) (q_max(0.5 * (a + b)) > v ? a : b) = 0.5 * (a + b);
      psi_points.push_back(0.5 * (a + b));
    }
  }
  return outer(ray, tidy(psi_points), 1e-9, 1e-10) / kPi;
}

std::vector<double> ground_pi_step_first(const LambSurface& g, double mach, double elevation_rad, double eta,
                                         const std::vector<double>& t_hat) {
  const double rho = std::cos(elevation_rad), z = std::sin(elevation_rad);
  // The times at which phi is not smooth: the direct sound from the impact point, and each front's
  // leaky wave, first heard at min over the ray towards the listener of x r + M R.
  std::vector<double> singular{mach};
  for (double x : {g.alpha(), 1.0, g.rayleigh_tau()}) {
    auto arrival = [&](double r) { return x * r + mach * std::sqrt((rho - r) * (rho - r) + z * z); };
    singular.push_back(arrival(argmin(arrival, 0.0, rho)));
  }
  singular = tidy(singular);
  const double s_smooth = std::max({mach, g.rayleigh_tau(), singular.back()}) + 2;
  const double s_far = t_hat.back() + 60 * eta, h_max = eta / 2, h_min = eta / 512;
  std::vector<double> edges;
  for (std::size_t i = 0; i + 1 < singular.size(); ++i) panels(singular[i], singular[i + 1], h_min, h_max, edges);
  panels(singular.back(), s_smooth, h_min, h_max, edges);
  for (double x = s_smooth; x < s_far; x += h_max) edges.push_back(x);
  edges.push_back(std::max(s_far, s_smooth + h_max));
  edges = tidy(edges);
  // phi past s_smooth from its Chebyshev interpolant (48 nodes of the first kind, barycentric).
  const int n_cheb = 48;
  std::vector<double> cx(n_cheb), cy(n_cheb), cw(n_cheb);
  const double a = s_smooth, b = std::max(s_far, s_smooth + 1);
  for (int k = 0; k < n_cheb; ++k) {
    const double th = (2 * k + 1) * kPi / (2 * n_cheb);
    cx[k] = 0.5 * (a + b) + 0.5 * (b - a) * std::cos(th);
    cy[k] = ground_step_volume(g, mach, elevation_rad, cx[k]);
    cw[k] = (k % 2 ? -1 : 1) * std::sin(th);
  }
  auto interpolant = [&](double s) {
    double num = 0, den = 0;
    for (int k = 0; k < n_cheb; ++k) {
      if (s == cx[k]) return cy[k];
      const double t = cw[k] / (s - cx[k]);
      num += t * cy[k], den += t;
    }
    return num / den;
  };
  const gsl_integration_glfixed_table* rule = gsl_integration_glfixed_table_alloc(8);
  std::vector<Node> nodes;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i)
    for (std::size_t k = 0; k < 8; ++k) {
      double x = 0, w = 0;
      gsl_integration_glfixed_point(edges[i], edges[i + 1], k, &x, &w, rule);
      nodes.push_back({x, w});
    }
  gsl_integration_glfixed_table_free(const_cast<gsl_integration_glfixed_table*>(rule));
  std::vector<double> phi(nodes.size());
  for (std::size_t j = 0; j < nodes.size(); ++j)
    phi[j] = nodes[j].s < s_smooth ? ground_step_volume(g, mach, elevation_rad, nodes[j].s) : interpolant(nodes[j].s);
  std::vector<double> out;
  for (double t : t_hat) {
    double sum = 0;
    for (std::size_t j = 0; j < nodes.size() && nodes[j].s < t + 60 * eta; ++j) sum += nodes[j].w * f_second(t - nodes[j].s, eta) * phi[j];
    out.push_back(-sum);
  }
  return out;
}

std::vector<double> ground_pi_regularized_overhead(const LambSurface& g, double mach, double eta, const std::vector<double>& t_hat) {
  Integrator integrate;
  const double t_from = -4;  // emission before the impact: the Lorentzian's precursor, kept from here
  std::vector<double> out;
  for (double t : t_hat) {
    const double big_r_max = (t - t_from) / mach;  // t - M R >= t_from
    if (!(big_r_max > 1)) {
      out.push_back(0);
      continue;
    }
    const double r_max = std::min(std::sqrt(big_r_max * big_r_max - 1), (t - t_from) / g.alpha() + 60 * eta);
    std::vector<double> points{0.0, r_max};
    for (double x : {g.alpha(), 1.0, g.rayleigh_tau()}) {
      std::vector<double> xs;
      for (int i = 0; i <= 64; ++i) xs.push_back(r_max * i / 64.0);
      roots([&](double r) { return t - mach * std::sqrt(1 + r * r) - x * r; }, xs, points);
    }
    auto integrand = [&](double r) {
      const double big_r = std::sqrt(1 + r * r), te = t - mach * big_r;
      return -g.regularized(te / r, eta / r, 2) / (r * r * big_r);
    };
    out.push_back(integrate(integrand, tidy(points), 1e-9, 1e-13));
  }
  return out;
}

}  // namespace clatter::reference
