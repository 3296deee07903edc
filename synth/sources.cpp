#include "synth/sources.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "io/pan_bank.hpp"
#include "kernels/pan/field.hpp"
#include "kernels/pan/render.hpp"

namespace clatter::synth {

PanSource::PanSource(const std::string& bank_path) : bank_(io::read_pan_bank(bank_path)) {
  if (bank_.proxies.empty()) throw InputError(bank_path + ": the bank holds no proxies");
  try {
    kernels::pan::check_direction_sets(bank_);
  } catch (const std::invalid_argument& e) {
    throw InputError(bank_path + ": " + e.what());
  }
}

// Shapes compare at the bank's A: (B, C) = A (b, c) / a.
std::array<double, 2> PanSource::shape_at_bank_a(const kernels::ProxyFit& fit) const {
  return {bank_.header.a_m * fit.b_m / fit.a_m, bank_.header.a_m * fit.c_m / fit.a_m};
}

std::size_t PanSource::nearest_proxy(const kernels::ProxyFit& fit) const {
  const auto [b, c] = shape_at_bank_a(fit);
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < bank_.proxies.size(); ++i) {
    const double db = bank_.proxies[i].b_m - b, dc = bank_.proxies[i].c_m - c, d = db * db + dc * dc;  // per impact: no hypot
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

std::vector<std::string> PanSource::coverage(const std::vector<ObjectModel>& models) const {
  std::vector<std::string> lines;
  for (const ObjectModel& m : models) {
    const auto [b, c] = shape_at_bank_a(m.proxy);
    const model::PanProxy& p = bank_.proxies[nearest_proxy(m.proxy)];
    const double d = std::hypot(p.b_m - b, p.c_m - c);
    if (d > kCoverage_m)
      lines.push_back(fmt::format("object {}: shape (B, C) = ({:.3f}, {:.3f}) m at A = {} m; the nearest PAN proxy ({:.3f}, {:.3f}) "
                                  "is {:.3f} m away (covered: within {:.3f} m): it sounds with that proxy's radiation",
                                  m.object->id, b, c, bank_.header.a_m, p.b_m, p.c_m, d, kCoverage_m));
  }
  return lines;
}

void PanSource::add(const Impact& im, const std::vector<Vec3>& listeners, int rate_hz, std::vector<std::vector<double>>& out) {
  for (std::size_t l = 0; l < listeners.size(); ++l) add_at(im, listeners[l], rate_hz, out[l]);
}

void PanSource::add_at(const Impact& im, const Vec3& listener, int rate_hz, std::vector<double>& out) const {
  const auto& fit = im.model->proxy;
  const std::size_t p = nearest_proxy(fit);
  const double beta = fit.a_m / bank_.header.a_m;
  // Listener and accelerations in the proxy frame (its axes are the body's principal axes).
  const Vec3& x0 = im.pose.position_m;
  const Vec3 body = rotate_inverse(im.pose.orientation_wxyz, {listener[0] - x0[0], listener[1] - x0[1], listener[2] - x0[2]});
  const Vec3 lp = kernels::to_proxy_frame(fit, body);
  const double r = std::sqrt(lp[0] * lp[0] + lp[1] * lp[1] + lp[2] * lp[2]);
  if (!(r > fit.a_m))
    throw InputError(fmt::format("listener ({}, {}, {}) is {:.4g} m from object {} at t = {} s, inside its bounding sphere "
                                 "(radius {:.4g} m)",
                                 listener[0], listener[1], listener[2], r, im.model->object->id, im.t_s, fit.a_m));
  const Vec3 n = kernels::to_proxy_frame(fit, im.direction_body), arm = kernels::to_proxy_frame(fit, im.contact_body_m);
  const double m = im.model->object->mass_kg, f = im.peak_force_n;
  const Vec3 torque{arm[1] * n[2] - arm[2] * n[1], arm[2] * n[0] - arm[0] * n[2], arm[0] * n[1] - arm[1] * n[0]};
  kernels::pan::HalfSineAcceleration a;
  a.t0_s = im.t_s;
  a.tau_s = im.tau_s;
  for (std::size_t i = 0; i < 3; ++i) {
    a.peak[i] = f * n[i] / m;                                  // translation, eq. (9) fields 1-3
    a.peak[3 + i] = f * torque[i] / fit.moments_kg_m2[i];      // rotation about the principal axes
  }
  kernels::pan::render_impact(bank_.header, bank_.proxies[p], beta, lp, a, rate_hz, 0.0, out);
}

}  // namespace clatter::synth
