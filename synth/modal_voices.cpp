// The modal source's set-up (003 section 5.4): banks read and indexed, and each object's voice:
// bank by nu class, nearest entry, base frequency, scale, and the modes it renders.
#include <fmt/format.h>

#include <cmath>
#include <nanoflann.hpp>
#include <numbers>

#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "io/modal_bank.hpp"
#include "io/object_bank.hpp"
#include "kernels/modal/patch_sampling.hpp"
#include "kernels/rigid_body.hpp"
#include "kernels/transfer/multipole.hpp"
#include "synth/modal_source.hpp"

namespace clatter::synth {

// The entries' normalized semi-axes as nanoflann's dataset: the nearest-proxy query of 003
// section 5.4, min ||a' - a-hat||_2.
struct ModalSource::EntryIndex {
  struct Points {
    const model::ModalBank* bank;
    std::size_t kdtree_get_point_count() const { return bank->entries.size(); }
    double kdtree_get_pt(std::size_t i, std::size_t d) const { return bank->entries[i].axes_m[d]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Points>, Points, 3, std::size_t>;
  explicit EntryIndex(const model::ModalBank& bank) : points{&bank}, tree(3, points, nanoflann::KDTreeSingleIndexAdaptorParams(8)) {}
  std::size_t nearest(const std::array<double, 3>& axes) const {
    std::size_t index = 0;
    double distance_sq = 0;
    tree.knnSearch(axes.data(), 1, &index, &distance_sq);
    return index;
  }
  Points points;
  Tree tree;
};

ModalSource::ModalSource(const std::vector<std::string>& paths, ModalOptions options,
                         const std::vector<std::string>& object_paths)
    : ModalSource(
          [&] {
            std::vector<model::ModalBank> banks;
            for (const auto& p : paths) banks.push_back(io::read_modal_bank(p));
            return banks;
          }(),
          paths, options,
          [&] {
            std::vector<model::ObjectBank> banks;
            for (const auto& p : object_paths) banks.push_back(io::read_object_bank(p));
            return banks;
          }(),
          object_paths) {}

ModalSource::ModalSource(std::vector<model::ModalBank> banks, std::vector<std::string> names, ModalOptions options,
                         std::vector<model::ObjectBank> object_banks, std::vector<std::string> object_names)
    : options_(options),
      banks_(std::move(banks)),
      names_(std::move(names)),
      object_banks_(std::move(object_banks)),
      object_names_(std::move(object_names)) {
  if (banks_.empty() && object_banks_.empty()) throw InputError("modal sound needs at least one modal bank or object bank");
  for (std::size_t b = 0; b < banks_.size(); ++b) {
    if (banks_[b].entries.empty()) throw InputError(names_[b] + ": the modal bank holds no entries");
    for (const auto& e : banks_[b].entries)
      if (e.transfer.order.size() != e.modes())
        throw InputError(fmt::format("{}: entry {} has no acoustic transfer for its modes", names_[b], e.sample));
    indices_.push_back(std::make_unique<EntryIndex>(banks_[b]));
  }
  for (std::size_t b = 0; b < object_banks_.size(); ++b)
    for (std::size_t i = 0; i < object_banks_[b].entries.size(); ++i) {
      const auto& e = object_banks_[b].entries[i];
      if (e.modal.transfer.order.size() != e.modal.modes())
        throw InputError(fmt::format("{}: entry {} has no acoustic transfer for its modes", object_names_[b], e.key));
      // The first bank given that holds a key voices it.
      object_keys_.emplace(e.key, std::make_pair(b, i));
    }
}

ModalSource::~ModalSource() = default;

// The bank of the object's nu class: the nearest nu within the tolerance (docs/materials.md).
std::size_t ModalSource::bank_for(const io::Scene& scene, const io::SceneObject& o) const {
  const model::Material& m = scene.materials.at(o.material);
  if (banks_.empty())
    throw InputError(fmt::format("{}: object {} has no own model in the object banks given and no modal bank (-m) to "
                                 "voice its proxy",
                                 o.where, o.id));
  std::size_t best = 0;
  double best_d = INFINITY;
  std::string known;
  for (std::size_t b = 0; b < banks_.size(); ++b) {
    const model::Material& bm = banks_[b].header.material;
    const double d = std::abs(bm.poisson - m.poisson);
    if (d < best_d) best_d = d, best = b;
    known += fmt::format("{}{} (nu {}, {})", b ? ", " : "", bm.name, bm.poisson, names_[b]);
  }
  if (!(best_d <= options_.poisson_tolerance))
    throw InputError(fmt::format("{}: material '{}' (poisson_ratio {}) has no modal bank: the banks given serve nu within {} "
                                 "of theirs: {}",
                                 o.where, o.material, m.poisson, options_.poisson_tolerance, known));
  return best;
}

std::pair<const model::ObjectEntry*, std::size_t> ModalSource::own_model_of(const io::Scene& scene,
                                                                          const io::SceneObject& o, std::string& why_not) {
  if (object_banks_.empty()) {
    why_not = "no object bank (-O) given";
    return {nullptr, 0};
  }
  if (!o.mesh) {
    why_not = "it is given by numbers, not a mesh, so no object bank can hold it";
    return {nullptr, 0};
  }
  auto hash = mesh_hashes_.find(o.mesh.get());
  if (hash == mesh_hashes_.end()) hash = mesh_hashes_.emplace(o.mesh.get(), io::mesh_hash(*o.mesh)).first;
  const std::string key = hash->second + "-" + o.material;
  const auto found = object_keys_.find(key);
  if (found == object_keys_.end()) {
    why_not = fmt::format("no object bank given holds its mesh {} in '{}' (key {})", o.mesh_path, o.material, key);
    return {nullptr, 0};
  }
  const auto [b, i] = found->second;
  const model::ObjectEntry& e = object_banks_[b].entries[i];
  // The entry is this object only if the solid is the same: its elasticity and its mass (which
  // set every frequency and shape), to 1e-6 (a mesh written in another frame changes the last bits).
  const model::Material& m = scene.materials.at(o.material);
  auto differs = [](double x, double y) { return !(std::abs(x - y) <= 1e-6 * std::abs(y)); };
  if (differs(m.youngs_pa, e.material.youngs_pa) || differs(m.poisson, e.material.poisson) || differs(o.mass_kg, e.mass_kg)) {
    why_not = fmt::format("{} holds its mesh as {} but for another solid (E {} Pa, nu {}, mass {} kg; the scene's {} Pa, {}, "
                          "{} kg)",
                          object_names_[b], key, e.material.youngs_pa, e.material.poisson, e.mass_kg, m.youngs_pa,
                          m.poisson, o.mass_kg);
    return {nullptr, 0};
  }
  return {&e, b};
}

// The entry's modes that the object renders, in the object's material, with the energy rule's
// radiation damping: into v.modes and the per-mode arrays.
void ModalSource::add_modes(const io::Scene& scene, const io::SceneObject& o, int rate_hz, double rho_air, double c_air,
                            double power_scale, ModalVoice& v) const {
  const model::ModalEntry& e = *v.modes_of;
  const double pi = std::numbers::pi;
  model::Material mat = scene.materials.at(o.material);
  mat.rho_kg_m3 = o.mass_kg / o.volume_m3;
  const double top_hz = std::min(options_.max_frequency_hz, 0.45 * rate_hz);
  v.band_reach_hz = e.frequencies_hz.back() / v.gamma;
  v.band_top_hz = top_hz;
  v.band_short = v.band_reach_hz < top_hz;
  const double f0_hz = e.frequencies_hz.front() / v.gamma;
  if (v.band_short && f0_hz < top_hz)
    v.band_share = std::log(std::max(v.band_reach_hz, f0_hz) / f0_hz) / std::log(top_hz / f0_hz);
  const auto& transfer = prepared_.at(&e).multipoles;
  for (std::size_t k = 0; k < e.modes(); ++k) {
    const double f_hz = e.frequencies_hz[k] / v.gamma, omega = 2 * pi * f_hz;
    // The far-field power per unit q^2 does not depend on gamma (p_gamma(gamma x) = (s / gamma) p(x)
    // over a sphere gamma times larger); the mode loses it at 2 xi_rad omega times its energy
    // (omega^2 q^2 / 2), so xi_rad = P / omega^3.
    const double power_w = power_scale * kernels::transfer::far_field_power_w(transfer[k], rho_air, c_air);
    const double xi_material = mat.damping_ratio(omega), xi_radiation = power_w / (omega * omega * omega);
    const double xi = xi_material + (options_.energy_rule ? xi_radiation : 0.0);
    if (f_hz > top_hz)
      ++v.skipped_high;
    else if (f_hz < options_.min_frequency_hz)
      ++v.skipped_low;
    else if (!(xi < 1))
      ++v.skipped_overdamped;
    else {
      v.modes.push_back(k);
      v.omega_rad_s.push_back(omega);
      v.damping_ratio.push_back(xi);
      v.radiated_power_w.push_back(power_w);
      v.radiation_damping.push_back(xi_radiation);
      v.max_radiation_share = std::max(v.max_radiation_share, xi_radiation / xi_material);
    }
  }
}

ModalVoice ModalSource::make_voice(const io::Scene& scene, const ObjectModel& model, int rate_hz) {
  const io::SceneObject& o = *model.object;
  ModalVoice v;
  auto need_damping = [&] {
    if (!scene.materials.at(o.material).damping)
      throw InputError(fmt::format("{}: materials.{}: modal sound needs rayleigh_alpha_1_s and rayleigh_beta_s", scene.path,
                                   o.material));
  };
  // 003 section 5.4: below the threshold, the object's own model when a bank holds it.
  if (o.base_frequency_hz > 0 && o.base_frequency_hz < options_.proxy_above_hz) {
    const auto [own, b] = own_model_of(scene, o, v.own_model_missing);
    if (own) {
      need_damping();
      v.own_model = true;
      v.bank = b;
      v.object_entry = own;
      v.modes_of = &own->modal;
      v.base_frequency_hz = o.base_frequency_hz;
      v.base_frequency_from = o.base_frequency_from.empty() ? "scene" : o.base_frequency_from;
      prepare(own->modal, true);
      const auto& t = object_banks_[b].header.transfer;
      // Unscaled, on its own surface: gamma = 1, shapes as stored (the mass matches), no area bound.
      add_modes(scene, o, rate_hz, t.air_density_kg_m3, t.sound_speed_m_s, 1.0, v);
      return v;
    }
  }
  v.bank = bank_for(scene, o);
  need_damping();
  const model::ModalBank& bank = banks_[v.bank];
  v.frame = kernels::modal::modal_proxy_frame(model.proxy);
  v.entry = indices_[v.bank]->nearest(v.frame.unit_axes);
  const model::ModalEntry& e = bank.entries[v.entry];
  v.modes_of = &e;
  const double pi = std::numbers::pi, omega_p0 = 2 * pi * e.frequencies_hz.front();
  const double unit_volume_m3 = 4.0 / 3.0 * pi * e.axes_m[0] * e.axes_m[1] * e.axes_m[2];
  // The object's own density (its mass over its volume), not the material's.
  model::Material mat = scene.materials.at(o.material);
  mat.rho_kg_m3 = o.mass_kg / o.volume_m3;
  const double cs_object = mat.shear_speed_m_s();
  if (o.base_frequency_hz > 0) {
    v.base_frequency_hz = o.base_frequency_hz;
    v.base_frequency_from = o.base_frequency_from.empty() ? "scene" : o.base_frequency_from;
  } else {
    // The bank's proxy at the object's volume, in the object's material: omega ~ c_s / size.
    const double size = std::cbrt(o.volume_m3 / unit_volume_m3);
    v.base_frequency_hz = e.frequencies_hz.front() * cs_object / bank.header.material.shear_speed_m_s() / size;
    v.base_frequency_from = "proxy";
    if (v.base_frequency_hz < options_.proxy_above_hz) own_model_of(scene, o, v.own_model_missing);
  }
  if (!(v.base_frequency_hz < options_.proxy_above_hz)) v.own_model_missing.clear();
  v.gamma = omega_p0 / (2 * pi * v.base_frequency_hz);
  // Bank shapes are mass-normalized for the unit proxy (mass M = rho_b V); eq. (9)'s gamma^(-3/2)
  // and a renormalization to the object's mass m give sqrt(M / m) for every gamma.
  v.shape_scale = std::sqrt(bank.header.material.rho_kg_m3 * unit_volume_m3 / o.mass_kg);
  // The energy rule (docs/synth.md "Energy account"). The bank's shapes, renormalized to the
  // object's mass (shape_scale), move the scaled proxy's surface at the object's own mean-square
  // velocity; radiated power goes with that velocity times the radiating area (P = rho c sigma S
  // <v_n^2>). Equi-frequency scaling makes the proxy of a flat or thin object far larger than it,
  // and that area radiates what the object's cannot: the bound scales the pressure by the square
  // root of the area ratio, never above 1, so covered objects (ratio ~1) keep their sound.
  const kernels::ProxyFit& fit = model.proxy;  // the object's area: its mesh's, else its equivalent ellipsoid's
  const double area_m2 = o.surface_area_m2 > 0 ? o.surface_area_m2 : kernels::ellipsoid_surface_area_m2(fit.a_m, fit.b_m, fit.c_m);
  v.surface_ratio = area_m2 /
                    (v.gamma * v.gamma * kernels::ellipsoid_surface_area_m2(e.axes_m[0], e.axes_m[1], e.axes_m[2]));
  if (options_.energy_rule && v.surface_ratio < 1) v.transfer_bound = std::sqrt(v.surface_ratio);
  prepare(e, false);
  const double power_scale = v.shape_scale * v.transfer_bound * v.shape_scale * v.transfer_bound;
  add_modes(scene, o, rate_hz, bank.header.transfer.air_density_kg_m3, bank.header.transfer.sound_speed_m_s, power_scale, v);
  return v;
}

const ModalSource::Prepared& ModalSource::prepare(const model::ModalEntry& e, bool own_surface) {
  Prepared& p = prepared_[&e];
  if (p.multipoles.empty())
    for (std::size_t k = 0; k < e.modes(); ++k) p.multipoles.push_back(kernels::transfer::stored_multipole(e.transfer, k));
  if (own_surface && !p.mesh) p.mesh = std::make_unique<kernels::transfer::MeshLocator>(e.surface_nodes_m, e.surface_faces);
  if (!own_surface && !p.ellipsoid)
    p.ellipsoid = std::make_unique<kernels::transfer::SurfaceLocator>(e.axes_m, e.surface_nodes_m, e.surface_faces);
  return p;
}

void ModalSource::begin(const io::Scene& scene, const std::vector<ObjectModel>& models, int rate_hz) {
  voices_.clear();
  resonator_.clear();
  transfer_short_.clear();
  stats_ = {};
  for (const ObjectModel& m : models) {
    voices_.push_back(make_voice(scene, m, rate_hz));
    ModalVoice& v = voices_.back();
    const auto& all = prepared_.at(v.modes_of).multipoles;
    for (const std::size_t k : v.modes) v.transfer.push_back(&all[k]);
    resonator_.emplace_back(v.modes.size() * scene.listeners_m.size(), std::numeric_limits<std::size_t>::max());
    ++stats_.objects;
    stats_.modes += v.modes.size();
    stats_.skipped_high += v.skipped_high;
    stats_.skipped_low += v.skipped_low;
    stats_.skipped_overdamped += v.skipped_overdamped;
    if (v.band_short) ++stats_.band_short;
    stats_.min_band_share = std::min(stats_.min_band_share, v.band_share);
    if (v.transfer_bound < 1) ++stats_.bounded;
    if (options_.energy_rule && v.max_radiation_share > 0.01) ++stats_.radiation_damped;
    if (v.own_model) ++stats_.own_models;
    if (!v.own_model_missing.empty()) ++stats_.own_model_missing;
    (v.base_frequency_from == "scene" ? stats_.from_scene : v.base_frequency_from == "mesh" ? stats_.from_mesh : stats_.from_proxy)++;
  }
  listeners_.assign(scene.listeners_m.size(), kernels::modal::ResonatorBank(rate_hz));
  energy_.clear();
  for (const ObjectModel& m : models) energy_.push_back({m.object->id});
}

std::vector<std::string> ModalSource::coverage(const std::vector<ObjectModel>& models) const {
  std::vector<std::string> lines;  // one per object, its reasons joined
  for (std::size_t i = 0; i < models.size() && i < voices_.size(); ++i) {
    const ModalVoice& v = voices_[i];
    std::string line;
    if (!v.own_model_missing.empty())
      line = fmt::format("its base frequency {:.4g} Hz (from the {}) is below --proxy-above-hz {:.4g} Hz: it should ring with its "
                         "own model, but {}; it rings with its proxy (clatter-bank object builds the model: docs/modal.md "
                         "\"Objects with their own models\")",
                         v.base_frequency_hz, v.base_frequency_from, options_.proxy_above_hz, v.own_model_missing);
    if (!v.own_model) {
      const auto& u = v.frame.unit_axes;  // a <= b <= c
      const auto& h = banks_[v.bank].header;
      if (!kernels::modal::patch_violation({u[0], u[1], u[2]}, {h.min_ratio, h.cigar_ratio}, 1e-9).empty())
        line += fmt::format("{}shape a/c = {:.3f}, b/c = {:.3f} is outside modal bank '{}''s patch (a/c >= {}, the cigar at "
                            "b/c = {}): it rings with the nearest entry's mode shapes, scaled to its base frequency {:.4g} Hz "
                            "(from the {})",
                            line.empty() ? "" : "; and its ", u[0] / u[2], u[1] / u[2], names_[v.bank], h.min_ratio,
                            h.cigar_ratio, v.base_frequency_hz, v.base_frequency_from);
    }
    if (v.band_short)
      line += fmt::format("{}modes reach {:.4g} Hz of the top {:.4g} Hz: {:.0f} % of its audible band from {:.4g} Hz (in "
                          "octaves; {} to a larger band has the rest: docs/modal.md \"Every audible mode\")",
                          line.empty() ? "its " : "; and its ", v.band_reach_hz,
                          v.band_top_hz, 100 * v.band_share,
                          v.modes_of->frequencies_hz.front() / v.gamma, v.own_model ? "an object bank" : "a modal bank");
    if (!line.empty()) lines.push_back(fmt::format("object {}: {}", models[i].object->id, line));
  }
  return lines;
}

}  // namespace clatter::synth
