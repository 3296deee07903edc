#pragma once
// The ground materials table of the ground soundbank (configs/ground-materials.toml,
// docs/ground.md): one TOML table per ground with youngs_pa, poisson, rho_kg_m3 and source. Every
// key is checked; any violation throws InputError with one line naming the file and line, the
// material and key, and the value, e.g.
// "ground-materials.toml:12: soil.poisson = 0.5: must be in (0, 0.5)".
#include <string>
#include <string_view>
#include <vector>

#include "model/ground_bank.hpp"

namespace clatter::io {

// The materials in file order, their grids empty. `source` (the file name) prefixes every message.
std::vector<model::GroundMaterial> parse_ground_materials(std::string_view toml_text, const std::string& source);

// configs/ground-materials.toml as it was when the binary was built (embedded by CMake), and its
// name for messages.
const std::string& builtin_ground_materials_toml();
inline constexpr const char* kBuiltinGroundMaterialsSource = "configs/ground-materials.toml (built in)";

// The built-in table, parsed once.
const std::vector<model::GroundMaterial>& builtin_ground_materials();

// The material called `name`; InputError "SOURCE: unknown ground material 'NAME' (known: a, b, ...)".
const model::GroundMaterial& find_ground_material(const std::vector<model::GroundMaterial>& materials,
                                                  const std::string& name, const std::string& source);

}  // namespace clatter::io
