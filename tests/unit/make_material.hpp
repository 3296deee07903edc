#pragma once
// model::Material from its constants, for tests and benchmarks (no name, no source).
#include <optional>

#include "model/material.hpp"

namespace clatter::test {

// E and nu alone (a scene material without density or damping).
inline model::Material elastic(double youngs_pa, double poisson) {
  model::Material m;
  m.youngs_pa = youngs_pa, m.poisson = poisson;
  return m;
}

// With Rayleigh damping, as modal sound needs.
inline model::Material damped(double youngs_pa, double poisson, double alpha_1_s, double beta_s) {
  model::Material m = elastic(youngs_pa, poisson);
  m.damping = model::RayleighDamping{alpha_1_s, beta_s};
  return m;
}

// A ground: E, nu and the density.
inline model::Material ground(double youngs_pa, double poisson, double rho_kg_m3) {
  model::Material m = elastic(youngs_pa, poisson);
  m.rho_kg_m3 = rho_kg_m3;
  return m;
}

// The dimensionless half-space of the kernels' tests: mu = 1 Pa and rho = 1 kg/m^3, so c_s = 1 m/s.
inline model::Material unit_ground(double poisson) { return ground(2 * (1 + poisson), poisson, 1.0); }

}  // namespace clatter::test
