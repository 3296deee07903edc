#pragma once
// A homogeneous, isotropic, linearly elastic material as plain data: the one material type of
// Clatter. io/materials.hpp reads it from configs/materials.toml (docs/materials.md) for every
// program (the modal bank, the ground bank, clatter-sim); a scene's materials (io/scene.hpp) and a
// ground bank's are the same type, so the synthesizer compares them field by field; the kernels
// (Hertz contact, the FEM element, Lamb's half-space) take it directly. Std only.
//
// Its ranges are written once, in material_rule() below: the table reader and the scene reader
// check each key through it, and check_material() checks a whole material made in code.
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

namespace clatter::model {

// C = alpha M + beta K, diagonal in the mass-normalized modes: 2 xi omega = alpha + beta omega^2.
struct RayleighDamping {
  double alpha_1_s = 0;
  double beta_s = 0;
};

struct Material {
  std::string name;
  // 0 only where a scene leaves it out (the ground sound then takes its ground bank's density);
  // every table entry has one.
  double rho_kg_m3 = 0;
  double youngs_pa = 0;
  double poisson = 0;
  // Optional: only modal sound needs it; grounds (soil, wax) have none. The modal bank refuses a
  // material without it (banks/modal/modal_spec.cpp).
  std::optional<RayleighDamping> damping;
  // Optional fracture data for a later fracture model; absent = not given.
  std::optional<double> fracture_energy_j_m2;  // critical energy release rate G_c, J/m^2
  std::optional<double> tensile_strength_pa;   // tensile strength, Pa
  std::string source;  // citation of the values, or how they were assumed

  // G = E / (2 (1 + nu)), Lamé mu.
  double shear_modulus_pa() const { return youngs_pa / (2 * (1 + poisson)); }
  // Lamé lambda = E nu / ((1 + nu)(1 - 2 nu)).
  double lame_lambda_pa() const { return youngs_pa * poisson / ((1 + poisson) * (1 - 2 * poisson)); }
  // c_s = sqrt(G / rho). At fixed nu every modal frequency of a given shape is proportional to it,
  // which is why one modal bank serves every material of its nu class.
  double shear_speed_m_s() const { return std::sqrt(shear_modulus_pa() / rho_kg_m3); }
  // c_p = sqrt((lambda + 2 mu) / rho) = c_s sqrt(2 (1 - nu) / (1 - 2 nu)), computed in the second
  // form, as the ground banks always have (their stored c_p keeps its last bit).
  double pressure_speed_m_s() const { return shear_speed_m_s() * std::sqrt(2 * (1 - poisson) / (1 - 2 * poisson)); }
  // c_R: the real root in (0, c_s) of Rayleigh's equation (2 - x)^2 = 4 sqrt(1 - x) sqrt(1 - a x),
  // x = (c_R / c_s)^2, a = (c_s / c_p)^2, by bisection (the root is unique there for -1 < nu < 1/2;
  // 60 halvings reach double precision, cheap for a derived value).
  double rayleigh_speed_m_s() const {
    const double c_s = shear_speed_m_s(), a = std::pow(c_s / pressure_speed_m_s(), 2);
    const auto f = [a](double x) { return (2 - x) * (2 - x) - 4 * std::sqrt(1 - x) * std::sqrt(1 - a * x); };
    double lo = 1e-9, hi = 1;  // f(0+) < 0 (to first order -2x(1 - a)), f(1) = 1 > 0
    for (int i = 0; i < 60; ++i) (f(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
    return c_s * std::sqrt(0.5 * (lo + hi));
  }
  // Of a mode at omega; 0 without damping.
  double damping_ratio(double omega_rad_s) const {
    if (!damping) return 0;
    return 0.5 * (damping->alpha_1_s / omega_rad_s + damping->beta_s * omega_rad_s);
  }
};

// The one place a material's numbers are checked: the rule `value` breaks as the key `key` of the
// table (rho_kg_m3, youngs_pa, poisson, rayleigh_alpha_1_s, rayleigh_beta_s,
// fracture_energy_j_m2, tensile_strength_pa), or nullptr when it is allowed (or the key is unknown).
inline const char* material_rule(std::string_view key, double value) {
  const bool finite = std::isfinite(value);  // inf and nan are TOML floats, but no material's
  if (key == "rho_kg_m3" || key == "youngs_pa" || key == "fracture_energy_j_m2" || key == "tensile_strength_pa")
    return finite && value > 0 ? nullptr : "must be > 0";
  // The bounds of a stable isotropic solid: bulk and shear moduli both positive.
  if (key == "poisson") return value > -1 && value < 0.5 ? nullptr : "must be in (-1, 0.5)";
  if (key == "rayleigh_alpha_1_s" || key == "rayleigh_beta_s") return finite && value >= 0 ? nullptr : "must be >= 0";
  return nullptr;
}

// A whole material (made in code, or a scene's): "key = value: rule" of its first bad number, or
// "" when all are allowed. A scene material's rho_kg_m3 of 0 means "not given" and is allowed when
// `density_optional`.
inline std::string check_material(const Material& m, bool density_optional = false) {
  const auto bad = [](const char* key, double x) -> std::string {
    const char* rule = material_rule(key, x);
    if (!rule) return {};
    std::ostringstream shown;  // 6 significant digits, as %g: "-3.25e+09", "0.625"
    shown << x;
    return std::string(key) + " = " + shown.str() + ": " + rule;
  };
  std::string out;
  if (!(density_optional && m.rho_kg_m3 == 0)) out = bad("rho_kg_m3", m.rho_kg_m3);
  if (out.empty()) out = bad("youngs_pa", m.youngs_pa);
  if (out.empty()) out = bad("poisson", m.poisson);
  if (out.empty() && m.damping) out = bad("rayleigh_alpha_1_s", m.damping->alpha_1_s);
  if (out.empty() && m.damping) out = bad("rayleigh_beta_s", m.damping->beta_s);
  if (out.empty() && m.fracture_energy_j_m2) out = bad("fracture_energy_j_m2", *m.fracture_energy_j_m2);
  if (out.empty() && m.tensile_strength_pa) out = bad("tensile_strength_pa", *m.tensile_strength_pa);
  return out;
}

}  // namespace clatter::model
