// The TOML pieces io/toml_detail.hpp declares: the guarded parse and the parts of every message.
#include "io/toml_detail.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

#include "core/errors.hpp"

namespace clatter::io::detail {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string shown(const toml::value& v) {
  switch (v.type()) {
    case toml::value_t::table: return "a table";
    case toml::value_t::array: return "an array";
    default: {
      std::string s = toml::format(v);
      while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
      return s;
    }
  }
}

std::string where(const std::string& source, const toml::value& v) {
  auto line = v.location().line();
  return line > 0 ? source + ":" + std::to_string(line) : source;
}

namespace {

// The line of the first byte sequence that is not UTF-8 (overlong forms and surrogates included),
// or 0. TOML documents must be UTF-8, and toml11 3.7 reads out of bounds reporting some of them
// (an invalid byte in a 'literal string'; found by tests/fuzz/fuzz_config).
std::size_t first_non_utf8_line(std::string_view text) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b == '\n') ++line;
    const std::size_t n = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xe ? 3 : (b >> 3) == 0x1e ? 4 : 0;
    if (n == 0 || i + n > text.size()) return line;
    std::uint32_t cp = n == 1 ? b : b & (0x7f >> n);
    for (std::size_t k = 1; k < n; ++k) {
      const auto c = static_cast<unsigned char>(text[i + k]);
      if ((c >> 6) != 0x2) return line;
      cp = (cp << 6) | (c & 0x3f);
    }
    const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return line;
    i += n;
  }
  return 0;
}

}  // namespace

toml::value parse_toml(std::string_view toml_text, const std::string& source) {
  if (const std::size_t line = first_non_utf8_line(toml_text))
    throw InputError(source + ":" + std::to_string(line) + ": malformed TOML: not UTF-8 text");
  toml::value root;
  try {
    std::istringstream in{std::string(toml_text)};
    root = toml::parse(in, source);
  } catch (const toml::exception& e) {  // syntax_error, and internal_error for some malformed strings
    // toml11's message is a multi-line picture; keep its first line and the line number.
    std::string what = e.what();
    std::string first = what.substr(0, what.find('\n'));
    if (first.rfind("[error] ", 0) == 0) first = first.substr(8);
    if (first.rfind("toml::", 0) == 0 && first.find(": ") != std::string::npos) first = first.substr(first.find(": ") + 2);
    auto line = e.location().line();
    throw InputError((line > 0 ? source + ":" + std::to_string(line) : source) + ": malformed TOML: " + first);
  }
  return root;
}

}  // namespace clatter::io::detail
