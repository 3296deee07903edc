// The ground source at run time (docs/synth.md "Ground sound"): per ground impact and listener,
// the distance D and elevation from the contact point's foot on z = 0, eta = eps / D with
// 4 eps = c_s t_c (004), the bank's Pi bilinear in (elevation, log eta), and the box average of
// p = A dPi/dt_hat over every output sample as a difference of Pi.
#include "synth/ground_source.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/errors.hpp"
#include "io/ground_bank.hpp"
#include "kernels/ground/ground_response.hpp"

namespace clatter::synth {
namespace {

// A grid's values within this relative distance of its ends count as on the grid: asin and log
// round differently from how the bank's builder wrote its grid, and that is no clamp worth a count.
constexpr double kOnGrid = 1e-9;
constexpr double kModulusTolerance = 0.01;  // the scene's ground moduli against the bank's

// Linear weights of x between its neighbours in an ascending grid, x clamped to the grid's ends.
struct Bracket {
  std::size_t lo = 0, hi = 0;
  double w_hi = 0;       // the weight of hi; lo gets 1 - w_hi
  bool clamped = false;  // x was outside the grid
};

double grid_span(const std::vector<double>& grid) { return std::max(std::abs(grid.front()), std::abs(grid.back())); }

// x beyond the grid's last value by more than the rounding kOnGrid allows.
bool past_end(const std::vector<double>& grid, double x) { return x > grid.back() + kOnGrid * grid_span(grid); }

Bracket bracket(const std::vector<double>& grid, double x) {
  Bracket b;
  if (x <= grid.front()) {
    b.clamped = x < grid.front() - kOnGrid * grid_span(grid);
    return b;
  }
  if (x >= grid.back()) {
    b.lo = b.hi = grid.size() - 1;
    b.clamped = past_end(grid, x);
    return b;
  }
  b.hi = static_cast<std::size_t>(std::upper_bound(grid.begin(), grid.end(), x) - grid.begin());
  b.lo = b.hi - 1;
  b.w_hi = (x - grid[b.lo]) / (grid[b.hi] - grid[b.lo]);
  return b;
}

// out[k] += weight * series(x0 + k step) for k in [k_in, k_out), where every x lies in
// [1, len - 2): cubic Lagrange through the four samples around x. Linear interpolation of Pi
// sampled at eta / 8 was 0.37 % of the pressure in L2 overhead (concrete, eta 0.1, 44.1 kHz; all
// the rest 0.04 %, docs/ground.md "The rendered sound against an independent route"); the
// cubic's error is fourth order. The inner loop of the ground source (most of its time).
// 32-bit indices so that the AVX clones convert and load four or eight at a time (series are far
// below 2^31 samples); chosen at load time like the resonators' (kernels/modal/resonator_bank.cpp).
// Each k is computed alone, without fused multiply-adds (-ffp-contract=off), so every clone gives
// the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void interpolate(const double* __restrict series, double weight, double x0, double step, std::int32_t k_in, std::int32_t k_out,
                 double* __restrict out) {
  for (std::int32_t k = k_in; k < k_out; ++k) {
    const double x = x0 + k * step;
    const auto i = static_cast<std::int32_t>(x);  // x >= 1: truncation is floor
    const double u = x - i, a = series[i - 1], b = series[i], c = series[i + 1], d = series[i + 2];
    const double um = u - 1, up = u + 1, ut = u - 2;
    out[k] += weight * (-u * um * ut * (1.0 / 6) * a + up * um * ut * 0.5 * b - up * u * ut * 0.5 * c + up * u * um * (1.0 / 6) * d);
  }
}

// How far past a series' last sample its tail is rendered, as a multiple of that sample's t_hat:
// the tail's pressure falls as t_hat^-3, so past 2 t_hat_last it holds 2^-5 = 3 % of the tail's energy
// (itself about 1e-6 of the whole sound's: docs/ground.md); Pi is held after it.
constexpr double kTailSpan = 2;  // 7.4 ms for concrete at 1 m (the series end near 3.7 ms)
constexpr double kTailNodes = 16;  // nodes of the tail's interpolation per t_hat of its start

double series_end(const model::GroundSeries& s) { return s.t_hat_start + static_cast<double>(s.pi.size() - 1) * s.dt_hat; }

// pi[k] += weight Pi(t_hat0 + k dt_hat): 0 before the series' first sample, cubic between samples
// (linear in the first and last interval, which lack a fourth), then the series' tail (for eta) up
// to kTailSpan times its last sample's t_hat, then held; a series without a tail holds its last
// value. Split into ranges so the middle loop has no branches.
void accumulate(const model::GroundSeries& s, double eta, double weight, double t_hat0, double dt_hat, std::vector<double>& pi,
                std::vector<double>& tail_nodes) {
  const std::size_t n = pi.size(), len = s.pi.size();
  if (len == 0 || weight == 0) return;
  const double x0 = (t_hat0 - s.t_hat_start) / s.dt_hat, step = dt_hat / s.dt_hat;  // in series samples
  const double last = static_cast<double>(len - 1);
  auto first_at_least = [&](double x) {  // the first k with x0 + k step >= x
    const double k = std::ceil((x - x0) / step);
    auto i = static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(n)));
    while (i > 0 && x0 + static_cast<double>(i - 1) * step >= x) --i;  // ceil's rounding, either way
    while (i < n && x0 + static_cast<double>(i) * step < x) ++i;
    return i;
  };
  auto linear = [&](std::size_t k) {
    const double x = x0 + static_cast<double>(k) * step;
    const auto i = std::min(static_cast<std::size_t>(x), len - 2);
    const double f = x - static_cast<double>(i);
    return s.pi[i] + f * (s.pi[i + 1] - s.pi[i]);
  };
  const std::size_t k_in = first_at_least(0), k_out = std::max(k_in, first_at_least(last));
  const bool cubic = len >= 4;
  const std::size_t k_c0 = cubic ? std::clamp(first_at_least(1), k_in, k_out) : k_out;
  const std::size_t k_c1 = cubic ? std::clamp(first_at_least(last - 1), k_c0, k_out) : k_out;
  for (std::size_t k = k_in; k < k_c0; ++k) pi[k] += weight * linear(k);
  interpolate(s.pi.data(), weight, x0, step, static_cast<std::int32_t>(k_c0), static_cast<std::int32_t>(k_c1), pi.data());
  for (std::size_t k = k_c1; k < k_out; ++k) pi[k] += weight * linear(k);
  if (s.tail.empty()) {
    for (std::size_t k = k_out; k < n; ++k) pi[k] += weight * s.pi.back();
    return;
  }
  const double t_cut = kTailSpan * series_end(s);
  std::size_t k_cut = k_out;  // the first sample at or past t_cut, from which the tail is held
  while (k_cut < n && t_hat0 + static_cast<double>(k_cut) * dt_hat < t_cut) ++k_cut;
  if (k_cut > k_out) {
    // The tail varies on the scale of t_hat itself (Re (t_hat + i eta)^-m, t_hat >> eta): its
    // closed form at nodes t_hat_a / kTailNodes apart, then the same cubic as the samples (its
    // error, (1/16)^4 120 / 24 = 8e-5 of the tail's Pi, is far below the float output's), instead
    // of two 9-term complex sums per output sample, which made the tail 15x the series' cost.
    const double t_a = t_hat0 + static_cast<double>(k_out) * dt_hat, delta = std::max(dt_hat, t_a / kTailNodes);
    const double y0 = (t_hat0 - t_a) / delta + 2, y_step = dt_hat / delta;  // node j sits at t_a + (j - 2) delta
    const auto count = static_cast<std::size_t>(y0 + static_cast<double>(k_cut) * y_step) + 4;
    tail_nodes.resize(count);
    for (std::size_t j = 0; j < count; ++j)
      tail_nodes[j] = kernels::ground::tail_antiderivative(s.tail, t_a + (static_cast<double>(j) - 2) * delta, eta);
    interpolate(tail_nodes.data(), weight, y0, y_step, static_cast<std::int32_t>(k_out), static_cast<std::int32_t>(k_cut), pi.data());
  }
  const double held = kernels::ground::tail_antiderivative(s.tail, t_cut, eta);
  for (std::size_t k = k_cut; k < n; ++k) pi[k] += weight * held;
}

const model::GroundMaterial& bank_material(const model::GroundBank& bank, const std::string& bank_name, const io::Scene& scene) {
  std::string names;
  for (const auto& m : bank.materials) {
    if (m.name == scene.ground_material) return m;
    names += (names.empty() ? "'" : ", '") + m.name + "'";
  }
  throw InputError(fmt::format("{}: ground_material: '{}' is not a material of the ground bank {}, which holds {}", scene.path,
                               scene.ground_material, bank_name, names.empty() ? "none" : names));
}

// One constant of the ground: the scene's value against the bank's, within kModulusTolerance.
void check_constant(const io::Scene& scene, const char* key, double scene_value, double bank_value, const std::string& bank_name) {
  const double relative = std::abs(scene_value - bank_value) / std::abs(bank_value);
  if (relative <= kModulusTolerance) return;
  throw InputError(fmt::format("{}: materials.{}.{}: {} differs from the ground bank's {} ({}, material '{}') by {:.3g} %: the "
                               "bank's series hold for its own ground; give it within {} %",
                               scene.path, scene.ground_material, key, scene_value, bank_value, bank_name, scene.ground_material,
                               100 * relative, 100 * kModulusTolerance));
}

// The scene's ground against the bank's, both model::Material (the density only where the scene
// gives one): the bank's series hold for its own ground only.
void check_same_ground(const io::Scene& scene, const model::Material& given, const model::Material& bank, const std::string& bank_name) {
  check_constant(scene, "youngs_modulus_pa", given.youngs_pa, bank.youngs_pa, bank_name);
  check_constant(scene, "poisson_ratio", given.poisson, bank.poisson, bank_name);
  if (given.rho_kg_m3 > 0) check_constant(scene, "density_kg_m3", given.rho_kg_m3, bank.rho_kg_m3, bank_name);
}

void check_grid(const model::GroundMaterial& m, const std::string& bank_name) {
  if (m.elevation_rad.empty() || m.eta.empty() || m.series.size() != m.elevation_rad.size() * m.eta.size())
    throw InputError(fmt::format("{}: ground material '{}': {} series for a grid of {} elevations x {} eta", bank_name, m.name,
                                 m.series.size(), m.elevation_rad.size(), m.eta.size()));
  for (const auto& s : m.series)
    if (!s.pi.empty() && !(s.dt_hat > 0))
      throw InputError(fmt::format("{}: ground material '{}': a series with dt_hat {}", bank_name, m.name, s.dt_hat));
}

}  // namespace

GroundSource::GroundSource(const std::string& bank_path) : GroundSource(io::read_ground_bank(bank_path), bank_path) {}

GroundSource::GroundSource(model::GroundBank bank, std::string name) : bank_(std::move(bank)), name_(std::move(name)) {
  if (bank_.materials.empty()) throw InputError(name_ + ": the ground bank holds no materials");
}

void GroundSource::begin(const io::Scene& scene, const std::vector<ObjectModel>& /*models*/, int /*rate_hz*/) {
  const model::GroundMaterial& m = bank_material(bank_, name_, scene);
  check_grid(m, name_);
  check_same_ground(scene, scene.materials.at(scene.ground_material), m, name_);
  for (std::size_t l = 0; l < scene.listeners_m.size(); ++l) {
    const Vec3& x = scene.listeners_m[l];
    if (!(x[2] > 0))
      throw InputError(fmt::format("{}: listeners[{}].position_m: ({}, {}, {}) is not above the ground (the plane z = 0): the "
                                   "ground sound needs z > 0",
                                   scene.path, l, x[0], x[1], x[2]));
  }
  // The series are for the bank's ground (its nu and c_s), so the amplitude takes the bank's too.
  try {
    kernels::ground::check_lamb_ground(m);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("{}: ground material '{}': {}", name_, m.name, e.what()));
  }
  medium_ = {&m, m.shear_speed_m_s(), bank_.rho0_kg_m3};
  log_eta_.clear();
  for (double eta : m.eta) log_eta_.push_back(std::log(eta));
  stats_ = {};
}

void GroundSource::add(const Impact& im, const std::vector<Vec3>& listeners, int rate_hz, std::vector<std::vector<double>>& out) {
  if (!im.on_ground) return;
  // The object's impulse points up, out of the ground; the ground takes its opposite, a load into
  // it. Only the vertical part drives the bank's (vertical point load) Lamb problem.
  const double vertical_n_s = im.impulse_world_n_s[2];
  if (!(vertical_n_s > 0)) {
    ++stats_.skipped_upward;
    return;
  }
  ++stats_.impacts;
  for (std::size_t l = 0; l < listeners.size(); ++l) add_at(im, vertical_n_s, listeners[l], rate_hz, out[l]);
}

void GroundSource::add_at(const Impact& im, double j_n_s, const Vec3& listener, int rate_hz, std::vector<double>& out) {
  const model::GroundMaterial& m = *medium_.material;
  const double dx = listener[0] - im.point_world_m[0], dy = listener[1] - im.point_world_m[1], z = listener[2];
  const double d_m = std::sqrt(dx * dx + dy * dy + z * z), elevation_rad = std::asin(std::min(1.0, z / d_m));
  const double c_s = medium_.shear_speed_m_s, dt_hat = c_s / (rate_hz * d_m);  // one output sample in t_hat
  // 004: 4 eps = c_s t_c. A pulse shorter than a sample has no audible shape; the box average below
  // keeps its integral, so eta is raised to one sample before the bank's own clamps.
  double eta = c_s * im.tau_s / 4 / d_m;
  // In log eta, with bracket's tolerance: an eta that rounds an ulp past eta_max is on the grid.
  if (im.sustained && past_end(log_eta_, std::log(eta))) {
    ++stats_.sustained_too_slow;
    return;
  }
  if (eta < dt_hat) eta = dt_hat, ++stats_.eta_below_sample;
  const Bracket be = bracket(m.elevation_rad, elevation_rad), bt = bracket(log_eta_, std::log(eta));
  if (be.clamped) ++stats_.elevation_outside;
  if (bt.clamped) ++(eta < m.eta.front() ? stats_.eta_below_grid : stats_.eta_above_grid);
  const std::array<std::size_t, 4> ie{be.lo, be.lo, be.hi, be.hi}, it{bt.lo, bt.hi, bt.lo, bt.hi};
  const std::array<double, 4> w{(1 - be.w_hi) * (1 - bt.w_hi), (1 - be.w_hi) * bt.w_hi, be.w_hi * (1 - bt.w_hi), be.w_hi * bt.w_hi};
  // The span of the four series in t_hat, then in output samples: from the first series sample (the
  // Lorentzian is non-causal, so it may precede the direct sound) to the end of the last tail.
  double t_hat_first = INFINITY, t_hat_last = -INFINITY;
  for (std::size_t q = 0; q < 4; ++q) {
    const model::GroundSeries& s = m.at(ie[q], it[q]);
    if (w[q] == 0 || s.pi.empty()) continue;
    t_hat_first = std::min(t_hat_first, s.t_hat_start);
    t_hat_last = std::max(t_hat_last, (s.tail.empty() ? 1 : kTailSpan) * series_end(s));
  }
  if (!(t_hat_last >= t_hat_first)) {
    ++stats_.no_series;
    return;
  }
  const double rate = rate_hz, to_s = d_m / c_s;
  const double n_first = std::floor((im.t_s + t_hat_first * to_s) * rate), n_last = std::ceil((im.t_s + t_hat_last * to_s) * rate) + 1;
  const auto n0 = static_cast<std::size_t>(std::clamp(n_first, 0.0, static_cast<double>(out.size())));
  const auto n1 = static_cast<std::size_t>(std::clamp(n_last, 0.0, static_cast<double>(out.size())));
  if (n1 <= n0) {
    ++stats_.outside_output;
    return;
  }
  pi_.assign(n1 - n0 + 1, 0.0);  // Pi at the sample edges t_n, n = n0 .. n1
  const double t_hat0 = (static_cast<double>(n0) / rate - im.t_s) / to_s;
  for (std::size_t q = 0; q < 4; ++q) accumulate(m.at(ie[q], it[q]), m.eta[it[q]], w[q], t_hat0, dt_hat, pi_, tail_nodes_);
  // Box average of p = A dPi/dt_hat over [t_n, t_n+1): A (Pi(t_n+1) - Pi(t_n)) / dt_hat.
  const double gain = kernels::ground::pressure_scale(*medium_.material, medium_.air_density_kg_m3, j_n_s, d_m) / dt_hat;
  for (std::size_t n = n0; n < n1; ++n) out[n] += gain * (pi_[n - n0 + 1] - pi_[n - n0]);
}

}  // namespace clatter::synth
