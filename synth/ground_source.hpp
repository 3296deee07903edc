#pragma once
// Ground sound from a ground soundbank (Qu & James, seed 004; docs/synth.md "Ground sound"): every
// impact of an object on the ground (the plane z = 0) sets the ground's surface moving (Lamb's
// problem, regularized over the Hertz contact), and its radiation reaches each listener as
//   p(t) = A dPi/dt_hat,   t_hat = c_s (t - t_impact) / D,   A = rho0 c_s^3 J / (mu D^3),
// with Pi(t_hat; elevation, eta) from the bank (model/ground_bank.hpp), interpolated bilinearly in
// (elevation, log eta), cubically between a series' samples and continued by its tail, and averaged
// over each output sample exactly, as a difference of Pi.
#include <string>
#include <vector>

#include "model/ground_bank.hpp"
#include "synth/sources.hpp"

namespace clatter::synth {

// Counts over one render. The clamps are per (impact, listener).
struct GroundStats {
  std::size_t impacts = 0;            // ground impacts rendered (each at every listener)
  std::size_t skipped_upward = 0;     // ground impacts whose impulse does not press into the ground
  std::size_t eta_below_sample = 0;   // eta raised to one sample period, c_s / (rate D)
  std::size_t eta_below_grid = 0;     // eta raised to the bank's eta_min
  std::size_t eta_above_grid = 0;     // eta lowered to the bank's eta_max
  std::size_t elevation_outside = 0;  // elevation clamped to the bank's grid
  // Sustained contacts (resting, sliding) whose load is slower than the bank's largest eta: a
  // quasi-static load radiates less than the slowest series, so they are skipped, not clamped
  // (clamping would sound a slow load as a click of its whole impulse).
  std::size_t sustained_too_slow = 0;
  std::size_t outside_output = 0;  // sound entirely outside the output's span (an impact past its end)
  std::size_t no_series = 0;       // the four neighbouring series of the grid are all empty
};

// The ground as the source uses it: the bank's material (the half-space) and the bank's air.
struct GroundMedium {
  const model::GroundMaterial* material = nullptr;
  double shear_speed_m_s = 0, air_density_kg_m3 = 0;
};

class GroundSource : public SoundSource {
 public:
  // From a file; InputError names it (wrong kind or version, no materials).
  explicit GroundSource(const std::string& bank_path);
  // A bank already in memory (tests, benchmarks); `name` stands for the file in messages.
  GroundSource(model::GroundBank bank, std::string name);

  std::string name() const override { return "ground"; }
  // Picks the bank's material named by the scene's ground_material and checks the scene's moduli
  // (and density, if given) against it, and every listener above the ground. InputError naming the
  // scene key and value, the bank and what it holds.
  void begin(const io::Scene& scene, const std::vector<ObjectModel>& models, int rate_hz) override;
  // Adds the ground's sound of an impact with b = ground; other impacts are not the ground's.
  void add(const Impact& impact, const std::vector<Vec3>& listeners_m, int rate_hz,
           std::vector<std::vector<double>>& out) override;

  const GroundStats& stats() const { return stats_; }
  const GroundMedium& medium() const { return medium_; }
  const model::GroundBank& bank() const { return bank_; }

 private:
  // One impact at one listener: D and elevation from the contact point's foot on z = 0.
  void add_at(const Impact& impact, double vertical_impulse_n_s, const Vec3& listener_m, int rate_hz, std::vector<double>& out);

  model::GroundBank bank_;
  std::string name_;
  GroundMedium medium_;
  std::vector<double> log_eta_;  // of the chosen material's grid
  std::vector<double> pi_;       // scratch: the interpolated Pi at the sample edges of one impact
  std::vector<double> tail_nodes_;  // scratch: one series' tail at its interpolation nodes
  GroundStats stats_;
};

}  // namespace clatter::synth
