#pragma once
// TOML reading shared by the schema-checked config (config.cpp) and the materials table
// (materials.cpp), so both give the same one-line messages: the parse with its UTF-8 guard, and
// the pieces every message is made of. Private to io/: it includes toml11.
#include <cstddef>
#include <string>
#include <string_view>
#include <toml.hpp>

namespace clatter::io::detail {

// The document; InputError "SOURCE:LINE: malformed TOML: WHAT" (one line) when it is not TOML.
toml::value parse_toml(std::string_view toml_text, const std::string& source);

// "SOURCE:LINE" of a value, SOURCE alone when toml11 knows no line.
std::string where(const std::string& source, const toml::value& v);

// The value as the user wrote it, for messages ("a table" and "an array" for those).
std::string shown(const toml::value& v);

// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace clatter::io::detail
