#pragma once
// A homogeneous, isotropic, linearly elastic material of the modal soundbank with Rayleigh
// damping, as plain data: what io/materials.hpp reads from configs/materials.toml
// (docs/materials.md) and what the bank builder and the synthesizer scale by. Std only.
#include <cmath>
#include <string>

namespace clatter::model {

struct Material {
  std::string name;
  double rho_kg_m3 = 0;
  double youngs_pa = 0;
  double poisson = 0;
  double rayleigh_alpha_1_s = 0;  // C = alpha M + beta K
  double rayleigh_beta_s = 0;
  std::string source;  // citation of the values, or how they were assumed

  // c_s = sqrt(G / rho), G = E / (2 (1 + nu)). At fixed nu every modal frequency of a given shape
  // is proportional to it, which is why one bank serves every material of its nu class.
  double shear_speed_m_s() const { return std::sqrt(youngs_pa / (2 * (1 + poisson) * rho_kg_m3)); }

  // Of a mode at omega: C = alpha M + beta K is diagonal in the mass-normalized modes, with
  // 2 xi omega = alpha + beta omega^2.
  double damping_ratio(double omega_rad_s) const {
    return 0.5 * (rayleigh_alpha_1_s / omega_rad_s + rayleigh_beta_s * omega_rad_s);
  }
};

}  // namespace clatter::model
