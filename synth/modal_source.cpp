// The modal source at run time (003 Algorithm 1, generate_proxy_sound): per impact, the forces
// mapped onto the proxy, the modal forces at the Appendix F contact point, each mode's exact
// half-sine response weighted by its transfer |p_k| at each listener; the ringing is deferred to
// one resonator per mode and listener (kernels/modal/resonator_bank.hpp).
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "core/stage_log.hpp"
#include "kernels/transfer/multipole.hpp"
#include "kernels/transfer/surface_interpolation.hpp"
#include "synth/modal_source.hpp"

namespace clatter::synth {

std::vector<double> ModalSource::modal_forces(const Impact& im) const {
  const ModalVoice& v = voices_.at(im.model->index);
  const model::ModalEntry& e = *v.modes_of;
  const Prepared& prepared = prepared_.at(&e);
  Vec3 f = im.direction_body;
  kernels::transfer::SurfacePoint at;
  if (v.own_model) {
    // The object's own surface, in its body frame: the contact point itself.
    at = prepared.mesh->locate(Eigen::Vector3d(im.contact_body_m[0], im.contact_body_m[1], im.contact_body_m[2]));
  } else {
    f = kernels::modal::to_modal_frame(v.frame, im.direction_body);  // R f_0 (003 section 5.2)
    const Vec3 x = kernels::modal::contact_point(e.axes_m, {-f[0], -f[1], -f[2]});
    at = prepared.ellipsoid->locate(Eigen::Vector3d(x[0], x[1], x[2]));
  }
  const std::size_t per_mode = 3 * e.surface_nodes_m.size();
  std::vector<double> g;
  g.reserve(v.modes.size());
  for (const std::size_t k : v.modes) {
    const Eigen::Vector3d u = at.vector(std::span<const double>(e.shapes.data() + k * per_mode, per_mode));
    g.push_back(u.x() * f[0] + u.y() * f[1] + u.z() * f[2]);
  }
  return g;
}

void ModalSource::add(const Impact& im, const std::vector<Vec3>& listeners, int rate_hz, std::vector<std::vector<double>>& out) {
  const ModalVoice& v = voices_.at(im.model->index);
  if (v.modes.empty()) return;
  const model::ModalEntry& e = *v.modes_of;
  const std::vector<double> g = modal_forces(im);
  std::vector<std::optional<kernels::modal::HalfSineResponse>> response(v.modes.size());
  for (std::size_t k = 0; k < v.modes.size(); ++k)
    if (g[k] != 0)
      response[k].emplace(v.omega_rad_s[k], v.damping_ratio[k], im.tau_s, im.peak_force_n * v.shape_scale * g[k]);
  // The energy account (docs/synth.md "Energy account"): once per excitation, not per listener.
  ObjectEnergy& account = energy_[im.model->index];
  if (std::any_of(response.begin(), response.end(), [](const auto& r) { return r.has_value(); })) ++account.impacts;
  for (std::size_t k = 0; k < v.modes.size(); ++k)
    if (response[k]) {
      account.injected_j += response[k]->energy_after_contact_j();
      account.radiated_j += 2 * v.radiated_power_w[k] * response[k]->free_square_integral();
    }
  std::vector<double> p(v.modes.size());
  const double c_air =
      (v.own_model ? object_banks_[v.bank].header.transfer : banks_[v.bank].header.transfer).sound_speed_m_s;
  const Vec3& x0 = im.pose.position_m;
  for (std::size_t l = 0; l < listeners.size(); ++l) {
    // v -> gamma^-1 R v in the unit proxy's frame (003 section 5.2), where the multipoles live; an
    // own model's are in the body frame itself.
    const Vec3 body = rotate_inverse(im.pose.orientation_wxyz, {listeners[l][0] - x0[0], listeners[l][1] - x0[1], listeners[l][2] - x0[2]});
    const Vec3 vp = v.own_model ? body : kernels::modal::to_modal_frame(v.frame, body);
    const double r_m = std::sqrt(vp[0] * vp[0] + vp[1] * vp[1] + vp[2] * vp[2]);
    const double transfer_from_m = v.own_model ? v.object_entry->radius_m : 2 * e.axes_m[2] * v.gamma;
    if (!(r_m > im.model->proxy.a_m))
      throw InputError(fmt::format("listener ({}, {}, {}) is {:.4g} m from object {} at t = {} s, inside its bounding sphere "
                                   "(radius {:.4g} m)",
                                   listeners[l][0], listeners[l][1], listeners[l][2], r_m, im.model->object->id, im.t_s,
                                   im.model->proxy.a_m));
    // Outside the object but inside the region where its scaled proxy's multipoles hold: equi-
    // frequency scaling made the proxy larger than the object (a low base frequency for its
    // shape: an object outside the bank's patch). No transfer to this listener: skipped, named.
    if (!(r_m >= transfer_from_m)) {
      ++stats_.transfer_short;
      auto& worst = transfer_short_[im.model->object->id];
      worst = std::max(worst, transfer_from_m);
      continue;
    }
    kernels::transfer::pressure_magnitudes(v.transfer, Eigen::Vector3d(vp[0], vp[1], vp[2]) / v.gamma, p.data());
    const double t0_s = im.t_s + r_m / c_air;  // the sound leaves the proxy's centre at contact
    const double destroyed_s = im.model->object->destroyed_s;  // its modes stop (heard r / c later)
    const auto stop = std::isfinite(destroyed_s) ? static_cast<std::int64_t>(std::ceil((destroyed_s + r_m / c_air) * rate_hz))
                                                 : std::numeric_limits<std::int64_t>::max();
    for (std::size_t k = 0; k < v.modes.size(); ++k) {
      const double weight = v.transfer_bound * v.shape_scale / v.gamma * p[k];  // p_gamma(gamma x) = (s / gamma) p(x)
      if (!response[k] || !(weight > 0)) {
        ++stats_.silent_modes;
        continue;
      }
      std::size_t& r = resonator_[im.model->index][l * v.modes.size() + k];
      if (r == std::numeric_limits<std::size_t>::max()) r = listeners_[l].add(response[k]->pole());
      listeners_[l].excite(r, t0_s, *response[k], weight, out[l]);
      listeners_[l].stop_at(r, stop);
      ++stats_.excitations;
    }
  }
}

void ModalSource::finish(std::vector<std::vector<double>>& out) {
  Stage stage("modal ringing");  // the resonators, after the event loop (the stage table's own line)
  for (std::size_t l = 0; l < listeners_.size(); ++l) {
    const kernels::modal::ResonatorCounts c = listeners_[l].render(options_.relative_floor, out[l]);
    stats_.resonators.resonators += c.resonators;
    stats_.resonators.injections += c.injections;
    stats_.resonators.mode_samples += c.mode_samples;
    stats_.resonators.stepped_samples += c.stepped_samples;
  }
  for (auto& r : resonator_) std::fill(r.begin(), r.end(), std::numeric_limits<std::size_t>::max());
  for (std::size_t i = 0; i < energy_.size(); ++i) {
    stats_.injected_j += energy_[i].injected_j;
    stats_.radiated_j += energy_[i].radiated_j;
    if (energy_[i].injected_j > 0 && energy_[i].radiated_j / energy_[i].injected_j > stats_.worst_ratio) {
      stats_.worst_ratio = energy_[i].radiated_j / energy_[i].injected_j;
      stats_.worst_object = energy_[i].object_id;
    }
  }
}

}  // namespace clatter::synth
