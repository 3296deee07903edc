#pragma once
// TOML reading shared by the schema-checked config (config.cpp) and the materials reader
// (materials.cpp), so both give the same one-line messages: the parse with its UTF-8 guard, and
// the pieces every message is made of. Private to io/: it includes toml11.
#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <toml.hpp>
#include <utility>
#include <vector>

namespace clatter::io::detail {

// The document; InputError "SOURCE:LINE: malformed TOML: WHAT" (one line) when it is not TOML.
toml::value parse_toml(std::string_view toml_text, const std::string& source);

// "SOURCE:LINE" of a value, SOURCE alone when toml11 knows no line.
std::string where(const std::string& source, const toml::value& v);

// The value as the user wrote it, for messages ("a table" and "an array" for those).
std::string shown(const toml::value& v);

// The value exactly as written in the file (toml11 would print 0.7 as 0.69999999999999996);
// tables and arrays as shown() says them.
inline std::string written(const toml::value& v) {
  if (v.is_table() || v.is_array()) return shown(v);
  const auto& at = v.location();
  const std::string line = at.line_str();
  if (at.line() > 0 && at.column() >= 1 && at.column() - 1 + at.region() <= line.size())
    return line.substr(at.column() - 1, at.region());
  return shown(v);
}

// A table's entries in the order they appear in the file: toml11 keeps tables unordered, and the
// first error reported (and a built-in table's order) should not depend on a hash.
template <class Table>
std::vector<std::pair<std::string, const toml::value*>> in_file_order(const Table& table) {
  std::vector<std::pair<std::string, const toml::value*>> entries;
  for (const auto& [name, v] : table) entries.emplace_back(name, &v);
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    const auto la = a.second->location().line(), lb = b.second->location().line();
    return la != lb ? la < lb : a.first < b.first;
  });
  return entries;
}

// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace clatter::io::detail
