#pragma once
// One reader for Clatter's material tables (configs/materials.toml, io/materials.cpp;
// configs/ground-materials.toml, io/ground_materials.cpp): one [name] table per material, numeric
// keys checked against their intervals, a required `source`, unknown keys named with a "did you
// mean"; every message one line "FILE:LINE: name.key = value: rule". Private to io/ (toml11).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.hpp"
#include "io/toml_detail.hpp"

namespace clatter::io::detail {

// One numeric key of material type M: where it goes and the open or closed interval it must lie in.
template <class M>
struct NumberKey {
  const char* name;
  double M::*field;
  double min, max;
  bool min_exclusive, max_exclusive;
  const char* rule;  // the interval as the message says it
};

inline constexpr const char* kSourceKey = "source";

template <class M>
bool in_range(const NumberKey<M>& k, double x) {
  if (!std::isfinite(x)) return false;  // inf and nan are TOML floats, but no material's
  if (k.min_exclusive ? !(x > k.min) : !(x >= k.min)) return false;
  return k.max_exclusive ? x < k.max : x <= k.max;
}

// The table's keys, numbers first, and an unknown one's message ("NOUN" names the table's kind).
template <class M, std::size_t N>
std::string unknown_key_message(const std::string& name, const std::array<NumberKey<M>, N>& keys, const std::string& noun) {
  std::vector<std::string> names;
  for (const auto& k : keys) names.emplace_back(k.name);
  names.emplace_back(kSourceKey);
  std::string msg = "unknown key '" + name + "'";
  const std::string* best = nullptr;
  std::size_t best_distance = 3;  // suggest only close matches
  for (const auto& k : names) {
    const std::size_t d = edit_distance(name, k);
    if (d < best_distance) best = &k, best_distance = d;
  }
  if (best) msg += " (did you mean '" + *best + "'?)";
  std::string all;
  for (const auto& k : names) all += (all.empty() ? "" : ", ") + k;
  return msg + "; a " + noun + " has " + all;
}

// One [name] table into an M; `table_value` is the table itself, for its line.
template <class M, std::size_t N>
M read_material(const std::string& name, const toml::value& table_value, const std::string& source,
                const std::array<NumberKey<M>, N>& keys, const std::string& noun) {
  M m;
  m.name = name;
  std::array<bool, N + 1> seen{};  // the numbers, then `source`
  for (const auto& entry : in_file_order(table_value.as_table())) {
    // Not a structured binding: clang 14 (the fuzz preset) cannot capture one in the lambda below.
    const auto& key = entry.first;
    const auto& v = entry.second;
    const std::string head = where(source, *v) + ": " + name + "." + key + " = " + written(*v) + ": ";
    if (key == kSourceKey) {
      if (!v->is_string()) throw InputError(head + "expected a string");
      m.source = static_cast<std::string>(v->as_string());
      if (m.source.empty()) throw InputError(head + "must name where the values come from");
      seen[N] = true;
      continue;
    }
    const auto it = std::find_if(keys.begin(), keys.end(), [&](const NumberKey<M>& k) { return key == k.name; });
    if (it == keys.end()) throw InputError(head + unknown_key_message(key, keys, noun));
    double x = 0;
    if (v->is_integer()) x = static_cast<double>(v->as_integer());
    else if (v->is_floating()) x = static_cast<double>(v->as_floating());
    else throw InputError(head + "expected a number");
    if (!in_range(*it, x)) throw InputError(head + it->rule);
    m.*(it->field) = x;
    seen[static_cast<std::size_t>(it - keys.begin())] = true;
  }
  for (std::size_t i = 0; i <= N; ++i)
    if (!seen[i])
      throw InputError(where(source, table_value) + ": [" + name + "]: missing key '" + (i < N ? keys[i].name : kSourceKey) + "'");
  return m;
}

// The materials in file order; "SOURCE: no NOUNs: expected [name] tables" when there are none.
template <class M, std::size_t N>
std::vector<M> parse_material_table(std::string_view toml_text, const std::string& source, const std::array<NumberKey<M>, N>& keys,
                                    const std::string& noun) {
  const toml::value root = parse_toml(toml_text, source);
  std::vector<M> out;
  for (const auto& [name, v] : in_file_order(root.as_table())) {
    if (!v->is_table())
      throw InputError(where(source, *v) + ": " + name + " = " + written(*v) +
                       ": expected a [material] table (settings belong inside one)");
    out.push_back(read_material(name, *v, source, keys, noun));
  }
  if (out.empty()) throw InputError(source + ": no " + noun + "s: expected [name] tables");
  return out;
}

// The material called `name`; InputError "SOURCE: unknown NOUN 'NAME' (known: a, b, ...)".
template <class M>
const M& find_in_table(const std::vector<M>& materials, const std::string& name, const std::string& source, const std::string& noun) {
  const auto it = std::find_if(materials.begin(), materials.end(), [&](const M& m) { return m.name == name; });
  if (it != materials.end()) return *it;
  std::string known;
  for (const auto& m : materials) known += (known.empty() ? "" : ", ") + m.name;
  throw InputError(source + ": unknown " + noun + " '" + name + "' (known: " + known + ")");
}

}  // namespace clatter::io::detail
