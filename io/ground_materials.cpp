#include "io/ground_materials.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "io/toml_detail.hpp"

namespace clatter::io {
namespace {

using detail::in_file_order;
using detail::where;
using detail::written;

// One numeric key: where it goes and the open interval it must lie in.
struct NumberKey {
  const char* name;
  double model::GroundMaterial::*field;
  double min, max;
  const char* rule;  // the interval as the message says it
};

constexpr double kInf = std::numeric_limits<double>::infinity();
const std::array<NumberKey, 3> kNumberKeys = {{
    {"youngs_pa", &model::GroundMaterial::youngs_pa, 0.0, kInf, "must be > 0"},
    // Narrower than a stable solid's (-1, 0.5): Lamb's closed form (kernels/ground/lamb.hpp) takes
    // nu > 0, and nu = 0.5 has no finite P-wave speed.
    {"poisson", &model::GroundMaterial::poisson, 0.0, 0.5, "must be in (0, 0.5)"},
    {"rho_kg_m3", &model::GroundMaterial::rho_kg_m3, 0.0, kInf, "must be > 0"},
}};
constexpr const char* kSourceKey = "source";

std::vector<std::string> key_names() {
  std::vector<std::string> names;
  for (const auto& k : kNumberKeys) names.emplace_back(k.name);
  names.emplace_back(kSourceKey);
  return names;
}

std::string unknown_key_message(const std::string& name) {
  std::string msg = "unknown key '" + name + "'";
  static const std::vector<std::string> names = key_names();
  const std::string* best = nullptr;
  std::size_t best_distance = 3;  // suggest only close matches
  for (const auto& k : names) {
    const std::size_t d = detail::edit_distance(name, k);
    if (d < best_distance) best = &k, best_distance = d;
  }
  if (best) msg += " (did you mean '" + *best + "'?)";
  std::string all;
  for (const auto& k : names) all += (all.empty() ? "" : ", ") + k;
  return msg + "; a ground material has " + all;
}

double read_number(const NumberKey& key, const toml::value& v, const std::string& head) {
  double x = 0;
  if (v.is_integer()) x = static_cast<double>(v.as_integer());
  else if (v.is_floating()) x = static_cast<double>(v.as_floating());
  else throw InputError(head + "expected a number");
  // Open intervals only; inf and nan are TOML floats, but no material's.
  if (!std::isfinite(x) || !(x > key.min) || !(x < key.max)) throw InputError(head + key.rule);
  return x;
}

// One [name] table into a GroundMaterial; `table_value` is the table itself, for its line.
model::GroundMaterial read_material(const std::string& name, const toml::value& table_value, const std::string& source) {
  model::GroundMaterial m;
  m.name = name;
  std::vector<bool> seen(kNumberKeys.size() + 1, false);
  for (const auto& entry : in_file_order(table_value.as_table())) {
    const auto& key = entry.first;
    const auto& v = entry.second;
    const std::string head = where(source, *v) + ": " + name + "." + key + " = " + written(*v) + ": ";
    if (key == kSourceKey) {
      if (!v->is_string()) throw InputError(head + "expected a string");
      m.source = static_cast<std::string>(v->as_string());
      if (m.source.empty()) throw InputError(head + "must name where the values come from");
      seen.back() = true;
      continue;
    }
    const auto it = std::find_if(kNumberKeys.begin(), kNumberKeys.end(), [&](const NumberKey& k) { return key == k.name; });
    if (it == kNumberKeys.end()) throw InputError(head + unknown_key_message(key));
    m.*(it->field) = read_number(*it, *v, head);
    seen[static_cast<std::size_t>(it - kNumberKeys.begin())] = true;
  }
  const std::vector<std::string> names = key_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (!seen[i]) throw InputError(where(source, table_value) + ": [" + name + "]: missing key '" + names[i] + "'");
  return m;
}

}  // namespace

std::vector<model::GroundMaterial> parse_ground_materials(std::string_view toml_text, const std::string& source) {
  const toml::value root = detail::parse_toml(toml_text, source);
  std::vector<model::GroundMaterial> out;
  for (const auto& [name, v] : in_file_order(root.as_table())) {
    if (!v->is_table())
      throw InputError(where(source, *v) + ": " + name + " = " + written(*v) +
                       ": expected a [material] table (settings belong inside one)");
    out.push_back(read_material(name, *v, source));
  }
  if (out.empty()) throw InputError(source + ": no ground materials: expected [name] tables");
  return out;
}

const std::vector<model::GroundMaterial>& builtin_ground_materials() {
  static const std::vector<model::GroundMaterial> materials =
      parse_ground_materials(builtin_ground_materials_toml(), kBuiltinGroundMaterialsSource);
  return materials;
}

const model::GroundMaterial& find_ground_material(const std::vector<model::GroundMaterial>& materials,
                                                  const std::string& name, const std::string& source) {
  const auto it = std::find_if(materials.begin(), materials.end(),
                               [&](const model::GroundMaterial& m) { return m.name == name; });
  if (it != materials.end()) return *it;
  std::string known;
  for (const auto& m : materials) known += (known.empty() ? "" : ", ") + m.name;
  throw InputError(source + ": unknown ground material '" + name + "' (known: " + known + ")");
}

}  // namespace clatter::io
