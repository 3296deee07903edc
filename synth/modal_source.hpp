#pragma once
// Modal sound from modal soundbanks (Zheng & James 2010, seed 003, sections 5.1-5.4 and
// Algorithm 1; docs/synth.md "Modal sound"): each object is voiced by the nearest ellipsoid of the
// bank of its material's nu class, scaled to ring at the object's base frequency; every impact
// excites the proxy's modes at the Appendix F contact point with the Hertz half-sine, and each
// mode radiates |p_k| of the bank's multipole at the listener. An object whose base frequency is
// below the proxy threshold (003 section 5.4) rings with its own model instead when an object bank
// holds its mesh in its material (docs/synth.md "Objects with their own models"): the same
// rendering on the entry's own modes, unscaled, at the contact point itself.
#include <complex>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "kernels/modal/modal_proxy.hpp"
#include "kernels/modal/resonator_bank.hpp"
#include "kernels/transfer/mesh_locator.hpp"
#include "kernels/transfer/multipole.hpp"
#include "kernels/transfer/surface_interpolation.hpp"
#include "model/modal_bank.hpp"
#include "model/object_bank.hpp"
#include "synth/sources.hpp"

namespace clatter::synth {

struct ModalOptions {
  double min_frequency_hz = 20;      // modes below this after scaling are inaudible: skipped
  double max_frequency_hz = 20000;   // and above this (or above 0.45 of the output rate)
  double poisson_tolerance = 0.015;  // a bank serves materials within this of its nu (docs/materials.md)
  double relative_floor = 1e-6;      // a mode stops 120 dB below the loudest mode of the render
  // The energy rule of docs/synth.md "Energy account": a scaled proxy radiates from at most the
  // object's area, and each mode decays by its radiation too. Off only to measure what it changes.
  bool energy_rule = true;
  // omega_proxy / 2 pi of 003 section 5.4: an object whose base frequency is below it rings with its
  // own model when an object bank holds it, and is listed in the coverage report when none does.
  // 2000 Hz: the value three of 003 Table 2's four examples use (docs/synth.md).
  double proxy_above_hz = 2000;
};

// How one object is voiced (fixed for the whole render).
struct ModalVoice {
  // The entry that voices the object: its proxy's (bank, entry of a modal bank) or, with
  // own_model, its own (object_entry of object bank `bank`).
  std::size_t bank = 0, entry = 0;
  const model::ModalEntry* modes_of = nullptr;
  bool own_model = false;
  const model::ObjectEntry* object_entry = nullptr;
  std::string own_model_missing;    // below the threshold without an own model: why (coverage)
  kernels::modal::ModalProxyFrame frame;
  double base_frequency_hz = 0;     // omega_0 / 2 pi
  std::string base_frequency_from;  // "scene", "mesh" (FEM of the object's mesh) or "proxy"
  double gamma = 1;                 // geometric scale of the proxy, 003 section 5.4
  double shape_scale = 1;           // sqrt(M_unit / m): bank shapes -> the object's (it carries m)
  std::vector<std::size_t> modes;   // entry modes rendered
  std::vector<double> omega_rad_s, damping_ratio;  // of those, scaled and in the object's material
  std::vector<const kernels::transfer::Multipole*> transfer;  // of those, the bank's (unscaled)
  // The energy rule (docs/synth.md "Energy account"). surface_ratio: the object's surface area (its
  // mesh's, else its equivalent ellipsoid's) over the scaled proxy's; transfer_bound:
  // min(1, sqrt(surface_ratio)), the factor on every mode's pressure that keeps the proxy from
  // radiating from more area than the object has.
  double surface_ratio = 1, transfer_bound = 1;
  std::vector<double> radiated_power_w;   // of the rendered modes: far-field power per unit q^2 (time-averaged)
  std::vector<double> radiation_damping;  // P / omega^3, included in damping_ratio (with the rule)
  double max_radiation_share = 0;         // max over modes of xi_rad / xi_material
  std::size_t skipped_high = 0, skipped_low = 0, skipped_overdamped = 0;
  bool band_short = false;          // the bank's last mode, scaled, is below the top frequency
  // The share of the object's audible band [f_0, top] that its modes reach, in octaves:
  // log(min(last mode, top) / f_0) / log(top / f_0); 1 when nothing is missing.
  double band_share = 1;
  double band_reach_hz = 0;         // the last mode, scaled (the top of what the object can ring)
  double band_top_hz = 0;           // the top of the audible band: --max-frequency or 0.45 x the rate
};

struct ModalStats {
  std::size_t objects = 0, modes = 0, skipped_high = 0, skipped_low = 0, skipped_overdamped = 0;
  std::size_t from_scene = 0, from_mesh = 0, from_proxy = 0;  // where omega_0 came from
  std::size_t own_models = 0;        // objects voiced by their own model (an object bank's entry)
  std::size_t own_model_missing = 0; // objects below the proxy threshold voiced by their proxy
  // Objects whose bank's last mode, scaled, falls below the top frequency (003 section 5.1: a bank
  // is all-frequency only for gamma small enough): their modes between the two are missing.
  std::size_t band_short = 0;
  double min_band_share = 1;         // the smallest band_share of any object
  // Impact-listener pairs skipped because the listener lies inside the scaled proxy's multipole
  // region though outside the object (an object whose proxy, scaled to its base frequency, is larger
  // than itself); the objects are named by transfer_short_objects().
  std::size_t transfer_short = 0;
  std::size_t excitations = 0, silent_modes = 0;  // mode-listener pairs excited; those with zero modal force or transfer
  kernels::modal::ResonatorCounts resonators;    // summed over listeners
  // The energy account (docs/synth.md "Energy account"), over every excitation of the render: the
  // rendered modes' energy when each contact ended, and what their rings radiate to the far field.
  double injected_j = 0, radiated_j = 0;
  double worst_ratio = 0;  // max over objects of radiated / injected
  int worst_object = 0;    // its id
  std::size_t bounded = 0;          // objects whose transfer the surface bound lowered
  std::size_t radiation_damped = 0; // objects with a mode whose radiation damping is > 1 % of its material's
};

// One object's energy account over a render.
struct ObjectEnergy {
  int object_id = 0;
  double injected_j = 0, radiated_j = 0;
  std::size_t impacts = 0;  // impacts that excited at least one of its modes
};

class ModalSource : public SoundSource {
 public:
  // Banks from files (modal banks, then object banks); InputError names the file (wrong kind or
  // version, empty). At least one of either.
  explicit ModalSource(const std::vector<std::string>& bank_paths, ModalOptions options = {},
                       const std::vector<std::string>& object_bank_paths = {});
  // Banks already in memory (tests, benchmarks); names stand for the files in messages.
  ModalSource(std::vector<model::ModalBank> banks, std::vector<std::string> names, ModalOptions options = {},
              std::vector<model::ObjectBank> object_banks = {}, std::vector<std::string> object_names = {});
  ~ModalSource() override;

  std::string name() const override { return "modal"; }
  void begin(const io::Scene& scene, const std::vector<ObjectModel>& models, int rate_hz) override;
  void add(const Impact& impact, const std::vector<Vec3>& listeners_m, int rate_hz,
           std::vector<std::vector<double>>& out) override;
  void finish(std::vector<std::vector<double>>& out) override;

  const ModalVoice& voice(std::size_t object) const { return voices_.at(object); }
  // Object id -> the distance its scaled proxy's transfer needs, for objects skipped at a listener.
  const std::map<int, double>& transfer_short_objects() const { return transfer_short_; }
  // Objects whose shape lies outside their bank's patch (a/c below its min_ratio), and objects
  // below the proxy threshold without an own model.
  std::vector<std::string> coverage(const std::vector<ObjectModel>& models) const override;
  // u_k(x_c) . f / |f| of every rendered mode (per unit force), x_c the Appendix F point.
  std::vector<double> modal_forces(const Impact& impact) const;
  const ModalStats& stats() const { return stats_; }
  const std::vector<ObjectEnergy>& energy() const { return energy_; }  // per object, after finish
  const std::vector<model::ModalBank>& banks() const { return banks_; }

 private:
  struct EntryIndex;  // a kd-tree over one bank's normalized axes
  // An entry's multipoles and the locator of its surface, built on the entry's first use.
  struct Prepared {
    std::vector<kernels::transfer::Multipole> multipoles;
    std::unique_ptr<kernels::transfer::SurfaceLocator> ellipsoid;  // a proxy's: rays from the centre
    std::unique_ptr<kernels::transfer::MeshLocator> mesh;          // an object's own: the nearest face
  };
  ModalVoice make_voice(const io::Scene& scene, const ObjectModel& model, int rate_hz);
  // The object bank entry of the object's mesh and material, or why there is none ("" and the entry).
  std::pair<const model::ObjectEntry*, std::size_t> own_model_of(const io::Scene& scene, const io::SceneObject& object,
                                                                 std::string& why_not);
  void add_modes(const io::Scene& scene, const io::SceneObject& object, int rate_hz, double rho_air, double c_air,
                 double power_scale, ModalVoice& v) const;
  std::size_t bank_for(const io::Scene& scene, const io::SceneObject& object) const;
  const Prepared& prepare(const model::ModalEntry& entry, bool own_surface);

  ModalOptions options_;
  std::vector<model::ModalBank> banks_;
  std::vector<std::string> names_;
  std::vector<model::ObjectBank> object_banks_;
  std::vector<std::string> object_names_;
  std::map<std::string, std::pair<std::size_t, std::size_t>> object_keys_;  // key -> (object bank, entry)
  std::map<const io::TriangleMesh*, std::string> mesh_hashes_;               // of the scene's meshes
  std::vector<std::unique_ptr<EntryIndex>> indices_;
  std::map<const model::ModalEntry*, Prepared> prepared_;
  std::vector<ModalVoice> voices_;
  std::map<int, double> transfer_short_;
  std::vector<kernels::modal::ResonatorBank> listeners_;     // one resonator bank per listener
  std::vector<std::vector<std::size_t>> resonator_;          // [object][listener * modes + k]
  std::vector<ObjectEnergy> energy_;  // [object]
  ModalStats stats_;
};

}  // namespace clatter::synth
