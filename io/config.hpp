#pragma once
// Typed, schema-checked configuration. Each command declares a Schema (every key with its type,
// default, range and meaning); a Config holds one value per key, from the defaults, then a TOML
// file, then `--set section.key=value` overrides, in that order. Any violation throws InputError
// with a one-line message naming the source (file:line or --set), the key and the value.
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace clatter::io {

// A list is an array of numbers; with Key::group = g > 1 it is written as an array of g-tuples
// ([[x, y, z], ...]) and stored flattened. A StringList is an array of strings (names), each
// checked against Key::choices when the key has them.
using RealList = std::vector<double>;
using StringList = std::vector<std::string>;
using Value = std::variant<std::int64_t, double, bool, std::string, RealList, StringList>;

// Inclusive or exclusive numeric bounds; the defaults allow everything finite.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
};

struct Key {
  std::string name;       // "section.key"
  Value default_value;    // its alternative fixes the key's type
  std::string help;       // one line; says the unit when the name does not
  Range range = {};       // numbers only
  std::vector<std::string> choices = {};  // strings and string lists only; empty: any string
  int group = 1;                          // lists only: tuple size (3 for points)
};

struct Schema {
  std::string title;      // first line of a printed config
  std::vector<Key> keys;  // sections print in order of first appearance
  const Key* find(std::string_view name) const;
};

class Config {
 public:
  // The schema's defaults. Throws std::logic_error if a default violates its own key's range.
  explicit Config(const Schema& schema);

  // Applies a TOML document; `source` (the file name) prefixes every message.
  void merge_toml(std::string_view toml_text, const std::string& source);
  // Applies one "section.key=value" override. Strings may be given bare or in double quotes.
  void set(std::string_view assignment);

  std::int64_t integer(std::string_view key) const;
  double real(std::string_view key) const;
  bool boolean(std::string_view key) const;
  const std::string& string(std::string_view key) const;
  const RealList& reals(std::string_view key) const;
  const StringList& strings(std::string_view key) const;

  // Every key with its effective value, as TOML with one comment line of help per key. Parsing
  // it back gives the same Config: this text is what a bank stores as provenance.
  std::string to_toml() const;

 private:
  template <class T>
  const T& get(std::string_view key) const;
  void assign(const Key& key, Value value, const std::string& where, const std::string& shown);
  const Schema* schema_;
  std::map<std::string, Value, std::less<>> values_;
};

}  // namespace clatter::io
