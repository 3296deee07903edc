#pragma once
// The one materials table of Clatter (configs/materials.toml, docs/materials.md), read into
// model::Material for every program: the modal bank, the ground bank, clatter-sim. One TOML table
// per material; rho_kg_m3, youngs_pa, poisson and source are required, the Rayleigh pair
// (rayleigh_alpha_1_s, rayleigh_beta_s: both or neither) and the fracture data
// (fracture_energy_j_m2, tensile_strength_pa) optional. Every key is checked (its range by
// model::material_rule); any violation throws InputError with one line naming the file and line,
// the material and key, and the value, e.g.
// "materials.toml:12: glass.poisson = 0.7: must be in (-1, 0.5)".
#include <string>
#include <string_view>
#include <vector>

#include "model/material.hpp"

namespace clatter::io {

// The materials in file order. `source` (the file name) prefixes every message.
std::vector<model::Material> parse_materials(std::string_view toml_text, const std::string& source);

// configs/materials.toml as it was when the binary was built (embedded by CMake, so it does not
// depend on the working directory), and its name for messages.
const std::string& builtin_materials_toml();
inline constexpr const char* kBuiltinMaterialsSource = "configs/materials.toml (built in)";

// The built-in table, parsed once.
const std::vector<model::Material>& builtin_materials();

// The table at `path` ("another materials file in the same format"), or the built-in one when
// `path` is empty; `source` is set to the name messages use for it.
std::vector<model::Material> read_materials(const std::string& path, std::string& source);

// The material called `name`; InputError "SOURCE: unknown material 'NAME' (known: a, b, ...)".
const model::Material& find_material(const std::vector<model::Material>& materials, const std::string& name,
                                     const std::string& source);

}  // namespace clatter::io
