#include "io/materials.hpp"

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

// One numeric key: where it goes and the open or closed interval it must lie in.
struct NumberKey {
  const char* name;
  double model::Material::*field;
  double min, max;
  bool min_exclusive, max_exclusive;
  const char* rule;  // the interval as the message says it
};

constexpr double kInf = std::numeric_limits<double>::infinity();
const std::array<NumberKey, 5> kNumberKeys = {{
    {"rho_kg_m3", &model::Material::rho_kg_m3, 0.0, kInf, true, false, "must be > 0"},
    {"youngs_pa", &model::Material::youngs_pa, 0.0, kInf, true, false, "must be > 0"},
    // The bounds of a stable isotropic solid: bulk and shear moduli both positive.
    {"poisson", &model::Material::poisson, -1.0, 0.5, true, true, "must be in (-1, 0.5)"},
    {"rayleigh_alpha_1_s", &model::Material::rayleigh_alpha_1_s, 0.0, kInf, false, false, "must be >= 0"},
    {"rayleigh_beta_s", &model::Material::rayleigh_beta_s, 0.0, kInf, false, false, "must be >= 0"},
}};
constexpr const char* kSourceKey = "source";

bool in_range(const NumberKey& k, double x) {
  if (!std::isfinite(x)) return false;  // inf and nan are TOML floats, but no material's
  if (k.min_exclusive ? !(x > k.min) : !(x >= k.min)) return false;
  return k.max_exclusive ? x < k.max : x <= k.max;
}

std::vector<std::string> key_names() {
  std::vector<std::string> names;
  for (const auto& k : kNumberKeys) names.emplace_back(k.name);
  names.emplace_back(kSourceKey);
  return names;
}

std::string unknown_key_message(const std::string& name) {
  std::string msg = "unknown key '" + name + "'";
  const std::string* best = nullptr;
  std::size_t best_distance = 3;  // suggest only close matches
  static const std::vector<std::string> names = key_names();
  for (const auto& k : names) {
    const std::size_t d = detail::edit_distance(name, k);
    if (d < best_distance) best = &k, best_distance = d;
  }
  if (best) msg += " (did you mean '" + *best + "'?)";
  std::string all;
  for (const auto& k : names) all += (all.empty() ? "" : ", ") + k;
  return msg + "; a material has " + all;
}

double read_number(const NumberKey& key, const toml::value& v, const std::string& head) {
  double x = 0;
  if (v.is_integer()) x = static_cast<double>(v.as_integer());
  else if (v.is_floating()) x = static_cast<double>(v.as_floating());
  else throw InputError(head + "expected a number");
  if (!in_range(key, x)) throw InputError(head + key.rule);
  return x;
}

// One [name] table into a Material; `table_value` is the table itself, for its line.
model::Material read_material(const std::string& name, const toml::value& table_value, const std::string& source) {
  model::Material m;
  m.name = name;
  std::vector<bool> seen(kNumberKeys.size() + 1, false);
  for (const auto& entry : in_file_order(table_value.as_table())) {
    // Not a structured binding: clang 14 (the fuzz preset) cannot capture one in the lambda below.
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

std::vector<model::Material> parse_materials(std::string_view toml_text, const std::string& source) {
  const toml::value root = detail::parse_toml(toml_text, source);
  std::vector<model::Material> out;
  for (const auto& [name, v] : in_file_order(root.as_table())) {
    if (!v->is_table())
      throw InputError(where(source, *v) + ": " + name + " = " + written(*v) +
                       ": expected a [material] table (settings belong inside one)");
    out.push_back(read_material(name, *v, source));
  }
  if (out.empty()) throw InputError(source + ": no materials: expected [name] tables");
  return out;
}

const std::vector<model::Material>& builtin_materials() {
  static const std::vector<model::Material> materials = parse_materials(builtin_materials_toml(), kBuiltinMaterialsSource);
  return materials;
}

const model::Material& find_material(const std::vector<model::Material>& materials, const std::string& name,
                                     const std::string& source) {
  const auto it = std::find_if(materials.begin(), materials.end(), [&](const model::Material& m) { return m.name == name; });
  if (it != materials.end()) return *it;
  std::string known;
  for (const auto& m : materials) known += (known.empty() ? "" : ", ") + m.name;
  throw InputError(source + ": unknown material '" + name + "' (known: " + known + ")");
}

}  // namespace clatter::io
