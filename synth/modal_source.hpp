#pragma once
// Modal sound from modal soundbanks (Zheng & James 2010, seed 003, sections 5.1-5.4 and
// Algorithm 1; docs/synth.md "Modal sound"): each object is voiced by the nearest ellipsoid of the
// bank of its material's nu class, scaled to ring at the object's base frequency; every impact
// excites the proxy's modes at the Appendix F contact point with the Hertz half-sine, and each
// mode radiates |p_k| of the bank's multipole at the listener.
#include <complex>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "kernels/modal/modal_proxy.hpp"
#include "kernels/modal/resonator_bank.hpp"
#include "kernels/transfer/multipole.hpp"
#include "kernels/transfer/surface_interpolation.hpp"
#include "model/modal_bank.hpp"
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
};

// How one object is voiced (fixed for the whole render).
struct ModalVoice {
  std::size_t bank = 0, entry = 0;
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
};

struct ModalStats {
  std::size_t objects = 0, modes = 0, skipped_high = 0, skipped_low = 0, skipped_overdamped = 0;
  std::size_t from_scene = 0, from_mesh = 0, from_proxy = 0;  // where omega_0 came from
  // Objects whose bank's last mode, scaled, falls below the top frequency (003 section 5.1: a bank
  // is all-frequency only for gamma small enough): their modes between the two are missing.
  std::size_t band_short = 0;
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
};

class ModalSource : public SoundSource {
 public:
  // Banks from files; InputError names the file (wrong kind or version, empty).
  explicit ModalSource(const std::vector<std::string>& bank_paths, ModalOptions options = {});
  // Banks already in memory (tests, benchmarks); names stand for the files in messages.
  ModalSource(std::vector<model::ModalBank> banks, std::vector<std::string> names, ModalOptions options = {});
  ~ModalSource() override;

  std::string name() const override { return "modal"; }
  void begin(const io::Scene& scene, const std::vector<ObjectModel>& models, int rate_hz) override;
  void add(const Impact& impact, const std::vector<Vec3>& listeners_m, int rate_hz,
           std::vector<std::vector<double>>& out) override;
  void finish(std::vector<std::vector<double>>& out) override;

  const ModalVoice& voice(std::size_t object) const { return voices_.at(object); }
  // Object id -> the distance its scaled proxy's transfer needs, for objects skipped at a listener.
  const std::map<int, double>& transfer_short_objects() const { return transfer_short_; }
  // Objects whose shape lies outside their bank's patch (a/c below its min_ratio).
  std::vector<std::string> coverage(const std::vector<ObjectModel>& models) const override;
  // u_k(x_c) . f / |f| of every rendered mode (per unit force), x_c the Appendix F point.
  std::vector<double> modal_forces(const Impact& impact) const;
  const ModalStats& stats() const { return stats_; }
  const std::vector<ObjectEnergy>& energy() const { return energy_; }  // per object, after finish
  const std::vector<model::ModalBank>& banks() const { return banks_; }

 private:
  struct EntryIndex;  // a kd-tree over one bank's normalized axes
  ModalVoice make_voice(const io::Scene& scene, const ObjectModel& model, int rate_hz);
  std::size_t bank_for(const io::Scene& scene, const io::SceneObject& object) const;
  // An entry's multipoles and surface locator, built on its first use; the multipoles.
  const std::vector<kernels::transfer::Multipole>& prepare_entry(std::size_t bank, std::size_t entry);

  ModalOptions options_;
  std::vector<model::ModalBank> banks_;
  std::vector<std::string> names_;
  std::vector<std::unique_ptr<EntryIndex>> indices_;
  std::vector<std::vector<std::vector<kernels::transfer::Multipole>>> multipoles_;  // [bank][entry], built on use
  std::vector<std::vector<std::unique_ptr<kernels::transfer::SurfaceLocator>>> locators_;  // the same
  std::vector<ModalVoice> voices_;
  std::map<int, double> transfer_short_;
  std::vector<kernels::modal::ResonatorBank> listeners_;     // one resonator bank per listener
  std::vector<std::vector<std::size_t>> resonator_;          // [object][listener * modes + k]
  std::vector<ObjectEnergy> energy_;  // [object]
  ModalStats stats_;
};

}  // namespace clatter::synth
