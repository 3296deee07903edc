#include "synth/sources.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "io/pan_bank.hpp"
#include "kernels/pan/field.hpp"
#include "kernels/pan/render.hpp"

namespace clatter::synth {

PanSource::PanSource(const std::string& proxy_bank, const std::vector<std::string>& object_banks) {
  if (proxy_bank.empty() && object_banks.empty()) throw InputError("PAN: no bank given (-b or -P)");
  auto load = [&](const std::string& path, bool proxies) {
    banks_.push_back(io::read_pan_bank(path));
    const model::PanBank& bank = banks_.back();
    try {
      kernels::pan::check_direction_sets(bank);
    } catch (const std::invalid_argument& e) {
      throw InputError(path + ": " + e.what());
    }
    std::size_t meshes = 0;
    for (std::size_t e = 0; e < bank.proxies.size(); ++e) {
      if (!bank.proxies[e].is_mesh()) {
        if (proxies) proxies_.push_back(e);
        continue;
      }
      ++meshes;
      const std::string& key = bank.proxies[e].mesh.key;
      if (std::none_of(keys_.begin(), keys_.end(), [&](const auto& k) { return k.first == key; }))
        keys_.push_back({key, {banks_.size() - 1, e}});
    }
    if (proxies && bank.proxies.empty()) throw InputError(path + ": the bank holds no proxies");
    if (!proxies && meshes == 0)
      throw InputError(path + ": -P: the bank holds no mesh entries (clatter-bank pan-object makes them; a proxy bank is -b)");
  };
  if (!proxy_bank.empty()) load(proxy_bank, true);
  for (const auto& path : object_banks) load(path, false);
}

void PanSource::begin(const io::Scene& scene, const std::vector<ObjectModel>& models, int) {
  own_.assign(scene.objects.size(), std::nullopt);
  std::vector<std::pair<const io::TriangleMesh*, std::string>> hashes;  // debris shares a few meshes
  for (const ObjectModel& m : models) {
    const io::SceneObject& o = *m.object;
    if (o.mesh && !keys_.empty()) {
      auto h = std::find_if(hashes.begin(), hashes.end(), [&](const auto& x) { return x.first == o.mesh.get(); });
      if (h == hashes.end()) h = hashes.insert(hashes.end(), {o.mesh.get(), io::mesh_hash(*o.mesh)});
      const auto k = std::find_if(keys_.begin(), keys_.end(), [&](const auto& x) { return x.first == h->second; });
      if (k != keys_.end()) own_[m.index] = k->second;
    }
    if (!own_[m.index] && proxies_.empty())
      throw InputError(fmt::format("{}: object {} has no PAN: no proxy bank (-b) given, and no -P bank holds {}", o.where,
                                   o.id, o.mesh ? fmt::format("its mesh {}", o.mesh_path) : std::string("an object given by numbers")));
  }
}

std::size_t PanSource::own_entries() const {
  return static_cast<std::size_t>(std::count_if(own_.begin(), own_.end(), [](const auto& r) { return r.has_value(); }));
}

// Shapes compare at the bank's A: (B, C) = A (b, c) / a.
std::array<double, 2> PanSource::shape_at_bank_a(const kernels::ProxyFit& fit) const {
  const double a = banks_.front().header.a_m;
  return {a * fit.b_m / fit.a_m, a * fit.c_m / fit.a_m};
}

std::size_t PanSource::nearest_proxy(const kernels::ProxyFit& fit) const {
  const auto [b, c] = shape_at_bank_a(fit);
  const auto& entries = banks_.front().proxies;
  std::size_t best = proxies_.front();
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i : proxies_) {
    const double db = entries[i].b_m - b, dc = entries[i].c_m - c, d = db * db + dc * dc;  // per impact: no hypot
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

std::vector<std::string> PanSource::coverage(const std::vector<ObjectModel>& models) const {
  std::vector<std::string> lines;
  for (const ObjectModel& m : models) {
    if (m.index < own_.size() && own_[m.index]) continue;  // its own entry: the object itself
    const auto [b, c] = shape_at_bank_a(m.proxy);
    const model::PanProxy& p = banks_.front().proxies[nearest_proxy(m.proxy)];
    const double d = std::hypot(p.b_m - b, p.c_m - c);
    if (d > kCoverage_m)
      lines.push_back(fmt::format("object {}: shape (B, C) = ({:.3f}, {:.3f}) m at A = {} m; the nearest PAN proxy ({:.3f}, {:.3f}) "
                                  "is {:.3f} m away (covered: within {:.3f} m): it sounds with that proxy's radiation",
                                  m.object->id, b, c, banks_.front().header.a_m, p.b_m, p.c_m, d, kCoverage_m));
  }
  return lines;
}

void PanSource::add(const Impact& im, const std::vector<Vec3>& listeners, int rate_hz, std::vector<std::vector<double>>& out) {
  for (std::size_t l = 0; l < listeners.size(); ++l) add_at(im, listeners[l], rate_hz, out[l]);
}

void PanSource::add_own(const Impact& im, const EntryRef& own, const Vec3& listener, int rate_hz, std::vector<double>& out) const {
  const model::PanBank& bank = banks_[own.bank];
  const model::PanProxy& entry = bank.proxies[own.entry];
  const io::SceneObject& o = *im.model->object;
  // The entry's frame is the body frame (the mesh's axes, its centre of mass at the origin) scaled
  // by the entry's scale: the object is the entry scaled by beta = 1 / scale.
  const double beta = 1.0 / entry.mesh.scale;
  const Vec3& x0 = im.pose.position_m;
  const Vec3 body = rotate_inverse(im.pose.orientation_wxyz, {listener[0] - x0[0], listener[1] - x0[1], listener[2] - x0[2]});
  const double r = std::sqrt(body[0] * body[0] + body[1] * body[1] + body[2] * body[2]);
  if (!(r > bank.header.a_m * beta))
    throw InputError(fmt::format("listener ({}, {}, {}) is {:.4g} m from object {} at t = {} s, inside its bounding sphere "
                                 "(radius {:.4g} m)",
                                 listener[0], listener[1], listener[2], r, o.id, im.t_s, bank.header.a_m * beta));
  const Vec3& n = im.direction_body;
  const Vec3& arm = im.contact_body_m;
  const double f = im.peak_force_n;
  const Vec3 torque{f * (arm[1] * n[2] - arm[2] * n[1]), f * (arm[2] * n[0] - arm[0] * n[2]), f * (arm[0] * n[1] - arm[1] * n[0])};
  // Angular acceleration I^-1 torque, I about the centre of mass in the mesh's axes (Cramer's rule).
  const auto& I = o.inertia_kg_m2;
  const double det = I[0][0] * (I[1][1] * I[2][2] - I[1][2] * I[2][1]) - I[0][1] * (I[1][0] * I[2][2] - I[1][2] * I[2][0]) +
                     I[0][2] * (I[1][0] * I[2][1] - I[1][1] * I[2][0]);
  auto column = [&](int k) {
    auto m = I;
    for (int i = 0; i < 3; ++i) m[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] = torque[static_cast<std::size_t>(i)];
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
            m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) / det;
  };
  kernels::pan::HalfSineAcceleration a;
  a.t0_s = im.t_s;
  a.tau_s = im.tau_s;
  for (std::size_t i = 0; i < 3; ++i) {
    a.peak[i] = f * n[i] / o.mass_kg;           // translation along the mesh's axes, fields 1-3
    a.peak[3 + i] = column(static_cast<int>(i));  // rotation about them through the centre of mass, fields 4-6
  }
  kernels::pan::render_impact(bank.header, entry, beta, body, a, rate_hz, 0.0, out);
}

void PanSource::add_at(const Impact& im, const Vec3& listener, int rate_hz, std::vector<double>& out) const {
  if (im.model->index < own_.size() && own_[im.model->index]) return add_own(im, *own_[im.model->index], listener, rate_hz, out);
  const auto& fit = im.model->proxy;
  const std::size_t p = nearest_proxy(fit);
  const model::PanBank& bank = banks_.front();
  const double beta = fit.a_m / bank.header.a_m;
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
  kernels::pan::render_impact(bank.header, bank.proxies[p], beta, lp, a, rate_hz, 0.0, out);
}

}  // namespace clatter::synth
