#include "io/materials.hpp"

#include <array>
#include <limits>

#include "io/material_table.hpp"

namespace clatter::io {
namespace {

using Key = detail::NumberKey<model::Material>;
constexpr double kInf = std::numeric_limits<double>::infinity();
const std::array<Key, 5> kNumberKeys = {{
    {"rho_kg_m3", &model::Material::rho_kg_m3, 0.0, kInf, true, false, "must be > 0"},
    {"youngs_pa", &model::Material::youngs_pa, 0.0, kInf, true, false, "must be > 0"},
    // The bounds of a stable isotropic solid: bulk and shear moduli both positive.
    {"poisson", &model::Material::poisson, -1.0, 0.5, true, true, "must be in (-1, 0.5)"},
    {"rayleigh_alpha_1_s", &model::Material::rayleigh_alpha_1_s, 0.0, kInf, false, false, "must be >= 0"},
    {"rayleigh_beta_s", &model::Material::rayleigh_beta_s, 0.0, kInf, false, false, "must be >= 0"},
}};
constexpr const char* kNoun = "material";

}  // namespace

std::vector<model::Material> parse_materials(std::string_view toml_text, const std::string& source) {
  return detail::parse_material_table(toml_text, source, kNumberKeys, kNoun);
}

const std::vector<model::Material>& builtin_materials() {
  static const std::vector<model::Material> materials = parse_materials(builtin_materials_toml(), kBuiltinMaterialsSource);
  return materials;
}

const model::Material& find_material(const std::vector<model::Material>& materials, const std::string& name,
                                     const std::string& source) {
  return detail::find_in_table(materials, name, source, kNoun);
}

}  // namespace clatter::io
