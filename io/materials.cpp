#include "io/materials.hpp"

#include <algorithm>
#include <array>
#include <optional>

#include "core/errors.hpp"
#include "io/text_file.hpp"
#include "io/toml_detail.hpp"

namespace clatter::io {
namespace {

using detail::where;
using detail::written;
using model::Material;

constexpr const char* kSourceKey = "source";
constexpr const char* kAlpha = "rayleigh_alpha_1_s";
constexpr const char* kBeta = "rayleigh_beta_s";
// Every key a material may have, required ones first (the order of the "a material has" list).
constexpr std::array<const char*, 8> kKeys = {"rho_kg_m3",         "youngs_pa",  "poisson", kSourceKey, kAlpha, kBeta,
                                              "fracture_energy_j_m2", "tensile_strength_pa"};
constexpr std::size_t kRequired = 4;

std::string unknown_key_message(const std::string& name) {
  std::string msg = "unknown key '" + name + "'";
  const char* best = nullptr;
  std::size_t best_distance = 3;  // suggest only close matches
  for (const char* k : kKeys) {
    const std::size_t d = detail::edit_distance(name, k);
    if (d < best_distance) best = k, best_distance = d;
  }
  if (best) msg += std::string(" (did you mean '") + best + "'?)";
  std::string all;
  for (const char* k : kKeys) all += (all.empty() ? "" : ", ") + std::string(k);
  return msg + "; a material has " + all + " (the last four optional)";
}

// The field a numeric key fills (the Rayleigh pair is assembled after the loop).
void store(Material& m, std::string_view key, double x, std::optional<double>& alpha, std::optional<double>& beta) {
  if (key == "rho_kg_m3") m.rho_kg_m3 = x;
  else if (key == "youngs_pa") m.youngs_pa = x;
  else if (key == "poisson") m.poisson = x;
  else if (key == kAlpha) alpha = x;
  else if (key == kBeta) beta = x;
  else if (key == "fracture_energy_j_m2") m.fracture_energy_j_m2 = x;
  else if (key == "tensile_strength_pa") m.tensile_strength_pa = x;
}

// One [name] table; `table_value` is the table itself, for its line.
Material read_material(const std::string& name, const toml::value& table_value, const std::string& source) {
  Material m;
  m.name = name;
  std::array<bool, kKeys.size()> seen{};
  std::optional<double> alpha, beta;
  for (const auto& [key, v] : detail::in_file_order(table_value.as_table())) {
    const std::string head = where(source, *v) + ": " + name + "." + key + " = " + written(*v) + ": ";
    const auto it = std::find_if(kKeys.begin(), kKeys.end(), [&k = key](const char* known) { return k == known; });
    if (it == kKeys.end()) throw InputError(head + unknown_key_message(key));
    seen[static_cast<std::size_t>(it - kKeys.begin())] = true;
    if (key == kSourceKey) {
      if (!v->is_string()) throw InputError(head + "expected a string");
      m.source = static_cast<std::string>(v->as_string());
      if (m.source.empty()) throw InputError(head + "must name where the values come from");
      continue;
    }
    double x = 0;
    if (v->is_integer()) x = static_cast<double>(v->as_integer());
    else if (v->is_floating()) x = static_cast<double>(v->as_floating());
    else throw InputError(head + "expected a number");
    if (const char* rule = model::material_rule(key, x)) throw InputError(head + rule);
    store(m, key, x, alpha, beta);
  }
  const std::string at = where(source, table_value) + ": [" + name + "]: ";
  for (std::size_t i = 0; i < kRequired; ++i)
    if (!seen[i]) throw InputError(at + "missing key '" + kKeys[i] + "'");
  if (alpha.has_value() != beta.has_value())
    throw InputError(at + "missing key '" + (alpha ? kBeta : kAlpha) + "': give both Rayleigh keys, or neither");
  if (alpha) m.damping = model::RayleighDamping{*alpha, *beta};
  return m;
}

}  // namespace

std::vector<Material> parse_materials(std::string_view toml_text, const std::string& source) {
  const toml::value root = detail::parse_toml(toml_text, source);
  std::vector<Material> out;
  for (const auto& [name, v] : detail::in_file_order(root.as_table())) {
    if (!v->is_table())
      throw InputError(where(source, *v) + ": " + name + " = " + written(*v) +
                       ": expected a [material] table (settings belong inside one)");
    out.push_back(read_material(name, *v, source));
  }
  if (out.empty()) throw InputError(source + ": no materials: expected [name] tables");
  return out;
}

const std::vector<Material>& builtin_materials() {
  static const std::vector<Material> materials = parse_materials(builtin_materials_toml(), kBuiltinMaterialsSource);
  return materials;
}

std::vector<Material> read_materials(const std::string& path, std::string& source) {
  source = path.empty() ? kBuiltinMaterialsSource : path;
  if (path.empty()) return builtin_materials();
  return parse_materials(read_text_file(path, "materials file"), path);
}

const Material& find_material(const std::vector<Material>& materials, const std::string& name, const std::string& source) {
  const auto it = std::find_if(materials.begin(), materials.end(), [&](const Material& m) { return m.name == name; });
  if (it != materials.end()) return *it;
  std::string known;
  for (const auto& m : materials) known += (known.empty() ? "" : ", ") + m.name;
  throw InputError(source + ": unknown material '" + name + "' (known: " + known + ")");
}

}  // namespace clatter::io
