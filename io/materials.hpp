#pragma once
// The materials table of the modal soundbank (configs/materials.toml, docs/materials.md): one
// TOML table per material with the keys of model::Material. Every key is checked; any violation
// throws InputError with one line naming the file and line, the material and key, and the value,
// e.g. "materials.toml:12: glass.poisson = 0.7: must be in (-1, 0.5)".
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

// The material called `name`; InputError "SOURCE: unknown material 'NAME' (known: a, b, ...)".
const model::Material& find_material(const std::vector<model::Material>& materials, const std::string& name,
                                     const std::string& source);

}  // namespace clatter::io
