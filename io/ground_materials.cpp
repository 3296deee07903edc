#include "io/ground_materials.hpp"

#include <array>
#include <limits>

#include "io/material_table.hpp"

namespace clatter::io {
namespace {

using Key = detail::NumberKey<model::GroundMaterial>;
constexpr double kInf = std::numeric_limits<double>::infinity();
const std::array<Key, 3> kNumberKeys = {{
    {"youngs_pa", &model::GroundMaterial::youngs_pa, 0.0, kInf, true, false, "must be > 0"},
    // Narrower than a stable solid's (-1, 0.5): Lamb's closed form (kernels/ground/lamb.hpp) takes
    // nu > 0, and nu = 0.5 has no finite P-wave speed.
    {"poisson", &model::GroundMaterial::poisson, 0.0, 0.5, true, true, "must be in (0, 0.5)"},
    {"rho_kg_m3", &model::GroundMaterial::rho_kg_m3, 0.0, kInf, true, false, "must be > 0"},
}};
constexpr const char* kNoun = "ground material";

}  // namespace

std::vector<model::GroundMaterial> parse_ground_materials(std::string_view toml_text, const std::string& source) {
  return detail::parse_material_table(toml_text, source, kNumberKeys, kNoun);
}

const std::vector<model::GroundMaterial>& builtin_ground_materials() {
  static const std::vector<model::GroundMaterial> materials =
      parse_ground_materials(builtin_ground_materials_toml(), kBuiltinGroundMaterialsSource);
  return materials;
}

const model::GroundMaterial& find_ground_material(const std::vector<model::GroundMaterial>& materials,
                                                  const std::string& name, const std::string& source) {
  return detail::find_in_table(materials, name, source, kNoun);
}

}  // namespace clatter::io
