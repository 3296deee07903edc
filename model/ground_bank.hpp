#pragma once
// The ground soundbank as plain data (docs/ground.md, docs/bank-format.md "Ground bank"): what
// `clatter-bank ground` builds, io/ground_bank.hpp stores, and clatter-synth interpolates. Std only.
//
// Why this grid. Lamb's problem has no length scale, so the Rayleigh integral of the unregularized
// step displacement, Phi_H, at a listener at distance D and elevation theta is
//   Phi_H(t) = (P / mu) phi(c_s t / D; theta, nu, M),   M = c_s / c0
// and 004's regularization of width eps only enters through eta = eps / D. The pressure of a unit
// impulse (1 N s) is then
//   p(t) = A dPi/dt_hat (t_hat = c_s t / D),   A = rho0 c_s^3 / (mu D^3),
//   Pi(t_hat) = -d^2/dt_hat^2 (f_eta * phi)(t_hat),
// so one material needs a 2-D grid (elevation, eta) of 1-D series, whatever the distances. The bank
// stores Pi, the pressure's antiderivative, so a synthesizer can average p over each output sample
// exactly (a difference of Pi), which band-limits pulses shorter than a sample.
#include <string>
#include <vector>

#include "model/material.hpp"
#include "model/sweep_status.hpp"

namespace clatter::model {

// The tail's number of coefficients (m = 2 .. kGroundTailTerms + 1), in a bank file and in memory.
inline constexpr std::size_t kGroundTailTerms = 9;

// Pi(t_hat) for one (elevation, eta), sampled at t_hat_start + k dt_hat, k = 0 .. pi.size() - 1.
// Before the first sample Pi is 0 (to the bank's precision). After the last it follows its tail,
//   Pi(t_hat) = sum_m tail[m - 2] (2 Re (t_hat + i eta)^-m - Re (t_hat + 2 i eta)^-m),  m = 2, 3, ...
// (kernels::ground::tail_antiderivative; tail[0] = (1 - nu) / (2 pi): the static field's share,
// Pi ~ tail[0] / t_hat^2); a series without tail coefficients stays constant after its last sample.
struct GroundSeries {
  double t_hat_start = 0, dt_hat = 0;
  std::vector<double> pi;
  std::vector<double> tail;
};

// One ground of the bank: the material (name, moduli, density, source; the bank stores no damping
// or fracture data) and its grid of series. It is a model::Material, so a scene's ground and the
// bank's are compared as the same type (synth/ground_source.cpp).
struct GroundMaterial : Material {
  std::vector<double> elevation_rad;      // ascending, in (0, pi/2]
  std::vector<double> eta;                // ascending, > 0 (log-spaced)
  std::vector<GroundSeries> series;       // [i_elevation * eta.size() + i_eta]
  const GroundSeries& at(std::size_t i_elevation, std::size_t i_eta) const { return series[i_elevation * eta.size() + i_eta]; }
};

struct GroundBank {
  double c0_m_s = 343.2, rho0_kg_m3 = 1.2041;  // the air the series were computed for (M = c_s / c0)
  std::vector<GroundMaterial> materials;
  // How complete the sweep was: a failed (material, elevation) task leaves that elevation out of
  // the material's grid (a material with none left is absent) and is named here.
  SweepStatus sweep;
};

}  // namespace clatter::model
