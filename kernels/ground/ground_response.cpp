#include "kernels/ground/ground_response.hpp"

#include "kernels/fem/tet_quadrature.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::kernels::ground {
namespace {

constexpr double kPi = std::numbers::pi;

struct Rule {
  std::vector<double> x, w;  // on [0, 1]
};

Rule gauss_legendre01(int n) {
  Rule r;
  fem::gauss_legendre_unit(n, r.x, r.w);
  return r;
}

void check(double mach, double elevation_rad) {
  if (!(mach > 0) || !std::isfinite(mach))
    throw std::invalid_argument("ground response: the Mach number c_s/c0 must be positive, not " + std::to_string(mach));
  if (!(elevation_rad > 0 && elevation_rad <= kPi / 2 + 1e-12))
    throw std::invalid_argument("ground response: the elevation must lie in (0, 90] degrees, not " +
                                std::to_string(elevation_rad * 180 / kPi) + " degrees");
}

// Panel edges on [lo, hi] graded towards `focus` (a panel is at most grading times its distance
// from the focus, at least `finest`, at most `longest`), plus every fixed edge inside.
std::vector<double> graded_edges(double lo, double hi, double focus, double finest, double longest, double grading,
                                 const std::vector<double>& fixed) {
  std::vector<double> e{lo, hi};
  for (double side = -1; side <= 1; side += 2) {
    double x = std::clamp(focus, lo, hi), step = finest;
    while (true) {
      const double dist = std::abs(x - focus);
      step = std::clamp(grading * dist, finest, longest);
      x += side * step;
      if (x <= lo || x >= hi) break;
      e.push_back(x);
    }
  }
  if (focus > lo && focus < hi) e.push_back(focus);
  for (double f : fixed)
    if (f > lo && f < hi) e.push_back(f);
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end(), [](double a, double b) { return b - a < 1e-14 * (1 + std::abs(a)); }), e.end());
  return e;
}

std::vector<double> merged(std::vector<double> a, const std::vector<double>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end(), [](double x, double y) { return y - x < 1e-14 * (1 + std::abs(x)); }), a.end());
  return a;
}

// Before the direct sound (s < M) q(r) rises from -inf at the impact point to a maximum and falls:
// where that maximum nears a front, the ray grazes it (a near-singular peak in r, a logarithmic
// singularity in psi). Golden section finds the maximum.
template <class Q>
double argmax(const Q& q, double lo, double hi) {
  const double k = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 100 && hi - lo > 1e-14 * hi; ++i) {
    const double x1 = hi - k * (hi - lo), x2 = lo + k * (hi - lo);
    (q(x1) > q(x2) ? hi : lo) = (q(x1) > q(x2) ? x2 : x1);
  }
  return 0.5 * (lo + hi);
}

// The panel that touches a Rayleigh front carries its 1/sqrt singularity (mapped away, see below);
// the panel after it sees the singularity just past its end, which Gauss-Legendre integrates well
// only if that panel is no longer than its distance to the front. A grading edge that happens to
// sit close to the front breaks that (the front moves with s, the grading edges do not), so such
// edges are dropped until the touching panel is at least half as long as the next one.
void widen_at_fronts(std::vector<double>& e, const std::vector<double>& fronts, const std::vector<double>& keep) {
  auto kept = [&](double x) {
    for (double k : keep)
      if (std::abs(k - x) <= 1e-13 * (1 + x)) return true;
    return false;
  };
  for (double c : fronts) {
    for (int side = -1; side <= 1; side += 2) {
      while (true) {
        const auto it = std::lower_bound(e.begin(), e.end(), c - 1e-13 * (1 + c));
        if (it == e.end() || !kept(*it)) break;
        const std::ptrdiff_t i = it - e.begin(), n = static_cast<std::ptrdiff_t>(e.size());
        const std::ptrdiff_t near = i + side, far = i + 2 * side;
        if (near <= 0 || near >= n - 1 || far < 0 || far > n - 1 || kept(e[static_cast<std::size_t>(near)])) break;
        const double touch = std::abs(e[static_cast<std::size_t>(near)] - c);
        const double next = std::abs(e[static_cast<std::size_t>(far)] - e[static_cast<std::size_t>(near)]);
        if (touch >= 0.5 * next) break;
        e.erase(e.begin() + near);
      }
    }
  }
}

struct Listener {
  double rho, z, mach;
};

// int_0^r_top S(q(r)) / R dr along the ray at angle psi from the listener's direction.
double ray_integral(const LambSurface& g, const Listener& l, double s, double psi, const Rule& rule, const VolumeSettings& set) {
  const double c = l.rho * std::cos(psi);
  auto big_r = [&](double r) { return std::sqrt(std::max(r * r - 2 * r * c + l.rho * l.rho + l.z * l.z, 0.0)); };
  auto q = [&](double r) { return (s - l.mach * big_r(r)) / r; };
  const double r_top = (s + l.mach) / (g.alpha() + l.mach);
  // Bracket the fronts q = alpha, 1, x_R on samples clustered towards the impact point (where the
  // fronts sit just after the direct sound), then bisect. Before the direct sound q rises to one
  // maximum and falls: with the maximum among the samples, each side is monotone and a grazing
  // pair of crossings, however close, is bracketed.
  const double fronts[3] = {g.alpha(), 1.0, g.rayleigh_tau()};
  const double r_star = s < l.mach ? argmax(q, 0.0, r_top) : 0.0;
  std::vector<double> samples;
  for (int i = 1; i <= set.ray_samples; ++i) {
    const double u = double(i) / set.ray_samples;
    samples.push_back(r_top * u * u * u);
  }
  if (r_star > 0) samples.insert(std::lower_bound(samples.begin(), samples.end(), r_star), r_star);
  std::vector<double> edges_fixed, rayleigh;
  double r_prev = 0, q_prev = s > l.mach ? INFINITY : -INFINITY;
  for (const double r : samples) {
    const double qi = q(r);
    for (int f = 0; f < 3; ++f) {
      const double v = fronts[f];
      if ((q_prev - v) * (qi - v) >= 0) continue;
      double a = r_prev, b = r;
      for (int it = 0; it < 60 && b - a > 1e-15 * b; ++it) {
        const double m = 0.5 * (a + b);
        ((q(m) - v) * (qi - v) > 0 ? b : a) = m;
      }
      edges_fixed.push_back(0.5 * (a + b));
      if (f == 2) rayleigh.push_back(0.5 * (a + b));
    }
    r_prev = r;
    q_prev = qi;
  }
  const double foot = std::clamp(c, 0.0, r_top), height = std::max(big_r(foot), 1e-12);
  std::vector<double> e = graded_edges(0, r_top, foot, set.finest_panel * height, set.longest_panel, set.grading, edges_fixed);
  if (s < l.mach) {
    // A ray that nearly grazes a front has a sharp peak at q's maximum: grade towards it.
    const double q_star = q(r_star);
    bool grazing = false;
    for (double v : fronts) grazing = grazing || std::abs(q_star - v) < 0.2 * v;
    if (grazing) e = merged(e, graded_edges(0, r_top, r_star, 1e-6 * r_top, set.longest_panel, 2.0, {}));
  }
  auto is_rayleigh = [&](double x) {
    for (double r : rayleigh)
      if (std::abs(r - x) <= 1e-13 * (1 + x)) return true;
    return false;
  };
  widen_at_fronts(e, rayleigh, edges_fixed);
  auto f = [&](double r) { return g.step(q(r)) / big_r(r); };
  double sum = 0;
  for (std::size_t p = 0; p + 1 < e.size(); ++p) {
    const double a = e[p], b = e[p + 1], h = b - a;
    const bool sa = is_rayleigh(a), sb = is_rayleigh(b);
    if (sa || sb) {
      // sqrt grading from the Rayleigh front, r = a + h w^2 (or b - h w^2): the one-sided 1/sqrt
      // singularity becomes a smooth integrand; split at the middle if both ends are fronts.
      const double m = (sa && sb) ? a + 0.5 * h : (sa ? b : a);
      for (std::size_t i = 0; i < rule.x.size(); ++i) {
        const double w = rule.x[i];
        if (sa) sum += rule.w[i] * 2 * (m - a) * w * f(a + (m - a) * w * w);
        if (sb) sum += rule.w[i] * 2 * (b - m) * w * f(b - (b - m) * w * w);
        if (!sa) sum += rule.w[i] * (m - a) * f(a + (m - a) * w);
        if (!sb) sum += rule.w[i] * (b - m) * f(m + (b - m) * w);
      }
      continue;
    }
    for (std::size_t i = 0; i < rule.x.size(); ++i) sum += rule.w[i] * h * f(a + h * rule.x[i]);
  }
  return sum;
}

// The angles psi at which the rays graze a front (max_r q = alpha, 1 or x_R), before the direct
// sound; max_r q falls as the ray turns away from the listener, so bisection in psi finds each.
std::vector<double> grazing_angles(const LambSurface& g, const Listener& l, double s) {
  std::vector<double> out;
  if (!(s < l.mach)) return out;
  const double r_top = (s + l.mach) / (g.alpha() + l.mach);
  auto q_max = [&](double psi) {
    const double c = l.rho * std::cos(psi);
    auto q = [&](double r) { return (s - l.mach * std::sqrt(std::max(r * r - 2 * r * c + l.rho * l.rho + l.z * l.z, 0.0))) / r; };
    return q(argmax(q, 0.0, r_top));
  };
  const double q0 = q_max(0), q_pi = q_max(kPi);
  for (double front : {g.alpha(), 1.0, g.rayleigh_tau()}) {
    if (!(q0 > front && q_pi < front)) continue;
    double a = 0, b = kPi;
    for (int i = 0; i < 60; ++i) ((q_max(0.5 * (a + b)) > front) ? a : b) = 0.5 * (a + b);
    out.push_back(0.5 * (a + b));
  }
  return out;
}

}  // namespace

double first_arrival(const LambSurface& g, double mach, double elevation_rad) {
  check(mach, elevation_rad);
  // min over the ray towards the listener of alpha r + M R(r): convex, so golden section.
  const double rho = std::cos(elevation_rad), z = std::sin(elevation_rad);
  auto t = [&](double r) { return g.alpha() * r + mach * std::sqrt((rho - r) * (rho - r) + z * z); };
  double a = 0, b = rho;
  const double k = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double x1 = b - k * (b - a), x2 = a + k * (b - a);
    (t(x1) < t(x2) ? b : a) = (t(x1) < t(x2) ? x2 : x1);
  }
  return std::min(mach, t(0.5 * (a + b)));
}

double step_volume(const LambSurface& g, double mach, double elevation_rad, double s, const VolumeSettings& set) {
  check(mach, elevation_rad);
  if (set.nodes_per_panel < 1 || !(set.grading > 0) || !(set.finest_panel > 0) || !(set.longest_panel > 0) || set.ray_samples < 8)
    throw std::invalid_argument("step_volume: the quadrature settings must be positive (ray_samples >= 8)");
  if (!(s > first_arrival(g, mach, elevation_rad))) return 0;
  const Listener l{std::cos(elevation_rad), std::sin(elevation_rad), mach};
  const Rule rule = gauss_legendre01(set.nodes_per_panel);
  if (l.rho < 1e-9) return ray_integral(g, l, s, 0, rule, set);  // overhead: axisymmetric
  // (1/2 pi) int_0^{2 pi} = (1/pi) int_0^pi; psi panels graded towards psi = 0, where the rays pass
  // under the listener (angular size of the peak: z / rho).
  std::vector<double> e = graded_edges(0, kPi, 0, set.finest_panel * l.z / l.rho, set.longest_panel, set.grading, {});
  for (double psi : grazing_angles(g, l, s)) e = merged(e, graded_edges(0, kPi, psi, 1e-5, set.longest_panel, 2.0, {}));
  double sum = 0;
  for (std::size_t p = 0; p + 1 < e.size(); ++p) {
    const double a = e[p], h = e[p + 1] - a;
    for (std::size_t i = 0; i < rule.x.size(); ++i) sum += rule.w[i] * h * ray_integral(g, l, s, a + h * rule.x[i], rule, set);
  }
  return sum / kPi;
}

namespace {

// phi's tail (ground_response.hpp): g[0 .. kTailTerms - 1] from phi's last sample, the slope of its
// last segment (so phi's slope has no jump where the tail takes over: a jump is a smoothed delta in
// Pi, a click of 1.3 % of the signal in L2 when the series was continued linearly) and step_volume
// at seven points, Chebyshev-spaced in u = s_join / s over [1/16, 1). Gaussian elimination with
// partial pivoting: the system is 9 x 9 in powers of u in [1/16, 1].
VolumeTail fit_tail(const LambSurface& g, double mach, double elevation_rad, const VolumeSeries& v, const VolumeSettings& set) {
  constexpr int n = kTailTerms;
  VolumeTail tail;
  tail.log_coefficient = g.static_value();
  const std::size_t last = v.phi.size() - 1;
  tail.s_join = v.s_start + static_cast<double>(last) * v.ds;
  const double s_join = tail.s_join, s_before = s_join - v.ds, c = tail.log_coefficient;
  std::vector<std::array<double, n + 1>> a(n);
  auto row = [&](int r, double u, double value) {
    for (int j = 0; j < n; ++j) a[static_cast<std::size_t>(r)][static_cast<std::size_t>(j)] = std::pow(u, j);
    a[static_cast<std::size_t>(r)][n] = value;
  };
  row(0, 1.0, v.phi[last] - c * std::log(s_join));
  for (int j = 0; j < n; ++j) a[1][static_cast<std::size_t>(j)] = 1 - std::pow(s_join / s_before, j);
  a[1][n] = (v.phi[last] - v.phi[last - 1]) - c * std::log(s_join / s_before);
  for (int k = 0; k < n - 2; ++k) {
    const double u = 1.0 / 16 + (15.0 / 16) * (1 - std::cos(kPi * k / (n - 2))) / 2, s = s_join / u;
    row(k + 2, u, step_volume(g, mach, elevation_rad, s, set) - c * std::log(s));
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t pivot = i;
    for (std::size_t r = i + 1; r < n; ++r)
      if (std::abs(a[r][i]) > std::abs(a[pivot][i])) pivot = r;
    std::swap(a[i], a[pivot]);
    for (std::size_t r = i + 1; r < n; ++r) {
      const double f = a[r][i] / a[i][i];
      for (std::size_t col = i; col <= n; ++col) a[r][col] -= f * a[i][col];
    }
  }
  tail.g.assign(n, 0.0);
  for (std::size_t i = n; i-- > 0;) {
    double sum = a[i][n];
    for (std::size_t col = i + 1; col < n; ++col) sum -= a[i][col] * tail.g[col];
    tail.g[i] = sum / a[i][i];
  }
  return tail;
}

}  // namespace

double VolumeTail::phi(double s) const {
  const double u = s_join / s;
  double sum = 0;
  for (std::size_t j = g.size(); j-- > 0;) sum = sum * u + g[j];
  return log_coefficient * std::log(s) + sum;
}

std::vector<double> VolumeTail::pi_tail() const {
  std::vector<double> out(g.size(), 0.0);
  if (g.empty()) return out;
  out[0] = log_coefficient;
  for (std::size_t j = 1; j < g.size(); ++j) {
    const double jd = static_cast<double>(j);
    out[j] = -g[j] * std::pow(s_join, jd) * jd * (jd + 1);
  }
  return out;
}

namespace {

// Re sum_k c[k] w^(k+2), w = 1 / (t + i e) = (t - i e) / (t^2 + e^2): Horner in real arithmetic
// (std::complex's division calls __divdc3 and keeps the loop from vectorizing).
inline double tail_sum(const double* c, std::size_t n, double t, double e) {
  const double inv = 1 / (t * t + e * e), w_re = t * inv, w_im = -e * inv;
  double re = 0, im = 0;
  for (std::size_t k = n; k-- > 0;) {
    const double r = re * w_re - im * w_im + c[k], i = re * w_im + im * w_re;
    re = r, im = i;
  }
  const double w2_re = w_re * w_re - w_im * w_im, w2_im = 2 * w_re * w_im;
  return re * w2_re - im * w2_im;
}

}  // namespace

double tail_antiderivative(const std::vector<double>& coefficients, double t_hat, double eta) {
  if (coefficients.empty()) return 0;
  return 2 * tail_sum(coefficients.data(), coefficients.size(), t_hat, eta) -
         tail_sum(coefficients.data(), coefficients.size(), t_hat, 2 * eta);
}


VolumeSeries step_volume_series(const LambSurface& g, double mach, double elevation_rad, double s_end, double ds,
                                const VolumeSettings& set) {
  VolumeSeries out;
  out.s_start = first_arrival(g, mach, elevation_rad);
  if (!(ds > 0) || !(s_end > out.s_start + 2 * ds))
    throw std::invalid_argument("step_volume_series: needs ds > 0 and s_end after the first arrival (" + std::to_string(out.s_start) + ")");
  out.ds = ds;
  const auto n = static_cast<std::size_t>(std::floor((s_end - out.s_start) / ds)) + 1;
  out.phi.resize(n);
  for (std::size_t k = 0; k < n; ++k) out.phi[k] = k == 0 ? 0.0 : step_volume(g, mach, elevation_rad, out.s_start + static_cast<double>(k) * ds, set);
  out.tail = fit_tail(g, mach, elevation_rad, out, set);
  return out;
}

PressureSeries pressure_antiderivative(const VolumeSeries& v, double eta, double t_start, double dt, double t_end) {
  if (!(eta > 0) || !(dt > 0) || !(t_end > t_start) || v.phi.size() < 3 || !(v.ds > 0) || v.tail.g.empty())
    throw std::invalid_argument("pressure_antiderivative: needs eta > 0, dt > 0, t_end > t_start and a sampled volume with its tail");
  // f_eta = 2 P_eta - P_2eta decays like eta^3 / x^4: past 400 eta a sample's weight is below
  // 1e-9 of its peak.
  const double reach = 400 * eta;
  // phi on one grid: the samples, then the tail out to where the last Pi sample stops seeing it.
  std::vector<double> phi = v.phi;
  const double s_last = t_end + reach + 2 * v.ds;
  for (std::size_t k = phi.size(); v.s_start + static_cast<double>(k - 1) * v.ds < s_last; ++k)
    phi.push_back(v.tail.phi(v.s_start + static_cast<double>(k) * v.ds));
  const std::size_t n = phi.size();
  // phi'' of the piecewise-linear phi: slope jumps at the samples (phi = 0 before the first).
  std::vector<double> kappa(n, 0.0);
  double slope_before = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double slope = (phi[i + 1] - phi[i]) / v.ds;
    kappa[i] = slope - slope_before;
    slope_before = slope;
  }
  auto f = [eta](double x) { return (2 * eta / (x * x + eta * eta) - 2 * eta / (x * x + 4 * eta * eta)) / kPi; };
  PressureSeries out;
  out.t_hat_start = t_start;
  out.dt_hat = dt;
  const auto m = static_cast<std::size_t>(std::floor((t_end - t_start) / dt)) + 1;
  out.pi.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    const double t = t_start + static_cast<double>(k) * dt;
    const double lo = std::max(0.0, std::ceil((t - reach - v.s_start) / v.ds));
    const double hi = std::min(double(n - 1), std::floor((t + reach - v.s_start) / v.ds));
    double sum = 0;
    for (auto i = static_cast<std::size_t>(lo); static_cast<double>(i) <= hi; ++i)
      sum += kappa[i] * f(t - (v.s_start + static_cast<double>(i) * v.ds));
    out.pi[k] = -sum;
  }
  return out;
}

double pressure_scale(const model::Material& ground, double rho0_kg_m3, double impulse_n_s, double distance_m) {
  if (!(distance_m > 0)) throw std::invalid_argument("pressure_scale: the listener's distance must be positive");
  const double cs = ground.shear_speed_m_s();
  return rho0_kg_m3 * impulse_n_s * cs * cs * cs / (ground.shear_modulus_pa() * distance_m * distance_m * distance_m);
}

}  // namespace clatter::kernels::ground
