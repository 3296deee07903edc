#include "io/config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <toml.hpp>

#include "core/errors.hpp"
#include "io/toml_detail.hpp"

namespace clatter::io {

using detail::shown;
using detail::where;

namespace {

// What a value of the key's type is called in messages.
template <class T>
const char* kind_name() {
  if constexpr (std::is_same_v<T, std::int64_t>) return "an integer";
  else if constexpr (std::is_same_v<T, double>) return "a number";
  else if constexpr (std::is_same_v<T, bool>) return "a boolean (true or false)";
  else if constexpr (std::is_same_v<T, std::string>) return "a string";
  else if constexpr (std::is_same_v<T, RealList>) return "an array of numbers";
  else return "an array of strings";
}
const char* kind_name(const Value& v) {
  return std::visit([](const auto& x) { return kind_name<std::decay_t<decltype(x)>>(); }, v);
}

std::string format_value(const Value& v) {
  return std::visit(
      [](const auto& x) -> std::string {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, RealList>) return "<list>";  // formatted by format_list
        else if constexpr (std::is_same_v<T, StringList>) {
          std::string out;
          for (const auto& e : x) out += (out.empty() ? "" : ", ") + toml::format(toml::value(e));
          return "[" + out + "]";
        } else if constexpr (std::is_same_v<T, std::string>) return toml::format(toml::value(x));
        else if constexpr (std::is_same_v<T, bool>) return x ? "true" : "false";
        else if constexpr (std::is_same_v<T, double>) {
          std::string s = fmt::format("{}", x);  // shortest round-trip form
          if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // stays a TOML float
          return s;
        } else return std::to_string(x);
      },
      v);
}

std::string format_list(const RealList& xs, int group) {
  std::string out = "[";
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (group > 1 && i % static_cast<std::size_t>(group) == 0) out += (i ? ", [" : "[");
    else if (i) out += ", ";
    out += format_value(xs[i]);
    if (group > 1 && (i + 1) % static_cast<std::size_t>(group) == 0) out += "]";
  }
  return out + "]";
}

// A TOML array of numbers, or of `group`-tuples of numbers, flattened; nullopt if it is neither.
std::optional<RealList> to_list(const toml::value& v, int group) {
  if (!v.is_array()) return std::nullopt;
  RealList out;
  auto number = [&](const toml::value& x) {
    if (x.is_integer()) return out.push_back(static_cast<double>(x.as_integer())), true;
    if (x.is_floating()) return out.push_back(static_cast<double>(x.as_floating())), true;
    return false;
  };
  for (const auto& e : v.as_array()) {
    if (group > 1) {
      if (!e.is_array() || e.as_array().size() != static_cast<std::size_t>(group)) return std::nullopt;
      for (const auto& x : e.as_array())
        if (!number(x)) return std::nullopt;
    } else if (!number(e)) {
      return std::nullopt;
    }
  }
  return out;
}

// A TOML array of strings; nullopt if it is not one.
std::optional<StringList> to_strings(const toml::value& v) {
  if (!v.is_array()) return std::nullopt;
  StringList out;
  for (const auto& e : v.as_array()) {
    if (!e.is_string()) return std::nullopt;
    out.push_back(static_cast<std::string>(e.as_string()));
  }
  return out;
}

std::string unknown_key_message(const Schema& schema, const std::string& name) {
  const Key* best = nullptr;
  std::size_t best_distance = 3;  // suggest only close matches
  for (const auto& k : schema.keys) {
    auto d = detail::edit_distance(name, k.name);
    if (d < best_distance) best = &k, best_distance = d;
  }
  std::string msg = "unknown key '" + name + "'";
  if (best) msg += " (did you mean '" + best->name + "'?)";
  return msg;
}

std::string range_text(const Range& r) {
  const bool has_min = std::isfinite(r.min), has_max = std::isfinite(r.max);
  if (has_min && has_max)
    return fmt::format("in {}{}, {}{}", r.min_exclusive ? "(" : "[", r.min, r.max, r.max_exclusive ? ")" : "]");
  if (has_min) return fmt::format("{} {}", r.min_exclusive ? ">" : ">=", r.min);
  return fmt::format("{} {}", r.max_exclusive ? "<" : "<=", r.max);
}

bool in_range(const Range& r, double x) {
  if (!std::isfinite(x)) return false;
  if (r.min_exclusive ? !(x > r.min) : !(x >= r.min)) return false;
  if (r.max_exclusive ? !(x < r.max) : !(x <= r.max)) return false;
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// One --set value of the key's type, from the text after '='. head: the message prefix.
Value parse_set_value(std::int64_t, const Key&, std::string_view text, const std::string& head) {
  std::int64_t n = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) throw InputError(head + "expected an integer");
  return n;
}
Value parse_set_value(double, const Key&, std::string_view text, const std::string& head) {
  const std::string s(text);
  char* end = nullptr;
  const double x = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size()) throw InputError(head + "expected a number");
  return x;
}
Value parse_set_value(bool, const Key&, std::string_view text, const std::string& head) {
  if (text != "true" && text != "false") throw InputError(head + "expected true or false");
  return text == "true";
}
Value parse_set_value(const std::string&, const Key&, std::string_view text, const std::string&) {
  return std::string(text);
}
Value parse_set_value(const RealList&, const Key& key, std::string_view text, const std::string& head) {
  std::optional<RealList> list;
  try {
    std::istringstream in("v = " + std::string(text));
    list = to_list(toml::find(toml::parse(in, "--set"), "v"), key.group);
  } catch (const std::exception&) {
  }
  if (!list) {
    if (key.group <= 1) throw InputError(head + "expected an array of numbers, e.g. [1, 2]");
    // The example has the key's own tuple size: a 2-tuple key shown 3-tuples misleads.
    RealList example(2 * static_cast<std::size_t>(key.group), 0.0);
    example[0] = example[static_cast<std::size_t>(key.group) + 1] = 1.0;
    throw InputError(head + "expected an array of " + std::to_string(key.group) + "-element arrays, e.g. " +
                     format_list(example, key.group));
  }
  return std::move(*list);
}

// A string list given as a TOML array (["a", "b"]) or bare (a,b: the shell needs no quotes).
Value parse_set_value(const StringList&, const Key&, std::string_view text, const std::string& head) {
  std::optional<StringList> names;
  if (!text.empty() && text.front() == '[') {
    try {
      std::istringstream in("v = " + std::string(text));
      names = to_strings(toml::find(toml::parse(in, "--set"), "v"));
    } catch (const std::exception&) {
    }
  } else {
    names.emplace();
    for (std::size_t at = 0; names && at <= text.size();) {
      const std::size_t comma = std::min(text.find(',', at), text.size());
      names->emplace_back(trim(text.substr(at, comma - at)));
      if (names->back().empty()) names.reset();
      at = comma + 1;
    }
  }
  if (!names) throw InputError(head + "expected names, e.g. a,b or [\"a\", \"b\"]");
  return std::move(*names);
}

}  // namespace

const Key* Schema::find(std::string_view name) const {
  auto it = std::find_if(keys.begin(), keys.end(), [&](const Key& k) { return k.name == name; });
  return it == keys.end() ? nullptr : &*it;
}

Config::Config(const Schema& schema) : schema_(&schema) {
  for (const auto& k : schema.keys) {
    if (k.name.find('.') == std::string::npos || k.name.find('.') != k.name.rfind('.'))
      throw std::logic_error("config key '" + k.name + "' must be section.key");
    const auto* x = std::get_if<double>(&k.default_value);
    const auto* n = std::get_if<std::int64_t>(&k.default_value);
    if ((x && !in_range(k.range, *x)) || (n && !in_range(k.range, static_cast<double>(*n))))
      throw std::logic_error("default of config key '" + k.name + "' is out of its range");
    values_[k.name] = k.default_value;
  }
}

void Config::assign(const Key& key, Value value, const std::string& source, const std::string& text) {
  const Value& want = key.default_value;
  // An integer is a fine value for a real-valued key.
  if (std::holds_alternative<double>(want) && std::holds_alternative<std::int64_t>(value))
    value = static_cast<double>(std::get<std::int64_t>(value));
  const std::string head = source + ": key '" + key.name + "' = " + text + ": ";
  if (value.index() != want.index()) throw InputError(head + "expected " + kind_name(want));
  if (const auto* n = std::get_if<std::int64_t>(&value); n && !in_range(key.range, static_cast<double>(*n)))
    throw InputError(head + "must be " + range_text(key.range));
  if (const auto* x = std::get_if<double>(&value); x && !in_range(key.range, *x))
    throw InputError(head + "must be " + range_text(key.range));
  if (const auto* list = std::get_if<RealList>(&value))
    for (std::size_t i = 0; i < list->size(); ++i)
      if (!in_range(key.range, (*list)[i]))
        throw InputError(head + "every element must be " + range_text(key.range) + fmt::format(", not [{}] = {}", i, (*list)[i]));
  if (const auto* str = std::get_if<std::string>(&value);
      str && !key.choices.empty() && std::find(key.choices.begin(), key.choices.end(), *str) == key.choices.end()) {
    std::string list;
    for (const auto& c : key.choices) list += (list.empty() ? "" : ", ") + c;
    throw InputError(head + "must be one of " + list);
  }
  if (const auto* names = std::get_if<StringList>(&value); names && !key.choices.empty())
    for (const auto& n : *names)
      if (std::find(key.choices.begin(), key.choices.end(), n) == key.choices.end()) {
        std::string list;
        for (const auto& c : key.choices) list += (list.empty() ? "" : ", ") + c;
        throw InputError(head + "'" + n + "' is not one of " + list);
      }
  values_[key.name] = std::move(value);
}

void Config::merge_toml(std::string_view toml_text, const std::string& source) {
  const toml::value root = detail::parse_toml(toml_text, source);
  for (const auto& [section, table] : root.as_table()) {
    if (!table.is_table()) {
      throw InputError(where(source, table) + ": " + unknown_key_message(*schema_, section) +
                       ": settings belong in a [section]");
    }
    for (const auto& [name, v] : table.as_table()) {
      const std::string full = section + "." + name;
      const Key* key = schema_->find(full);
      if (!key) throw InputError(where(source, v) + ": " + unknown_key_message(*schema_, full));
      Value value;
      switch (v.type()) {
        case toml::value_t::integer: value = static_cast<std::int64_t>(v.as_integer()); break;
        case toml::value_t::floating: value = static_cast<double>(v.as_floating()); break;
        case toml::value_t::boolean: value = static_cast<bool>(v.as_boolean()); break;
        case toml::value_t::string: value = static_cast<std::string>(v.as_string()); break;
        case toml::value_t::array:
          if (std::holds_alternative<StringList>(key->default_value)) {
            if (auto names = to_strings(v)) {
              value = std::move(*names);
              break;
            }
            throw InputError(where(source, v) + ": key '" + full + "' = " + shown(v) + ": expected an array of strings");
          }
          if (std::holds_alternative<RealList>(key->default_value)) {
            auto list = to_list(v, key->group);
            if (list) {
              value = std::move(*list);
              break;
            }
            throw InputError(where(source, v) + ": key '" + full + "' = " + shown(v) + ": expected " +
                             (key->group > 1 ? "an array of " + std::to_string(key->group) + "-element arrays of numbers"
                                             : std::string("an array of numbers")));
          }
          [[fallthrough]];
        default:
          throw InputError(where(source, v) + ": key '" + full + "' = " + shown(v) + ": expected " +
                           kind_name(key->default_value));
      }
      assign(*key, std::move(value), where(source, v), shown(v));
    }
  }
}

void Config::set(std::string_view assignment) {
  const std::string source = "--set '" + std::string(assignment) + "'";
  auto eq = assignment.find('=');
  if (eq == std::string_view::npos) throw InputError(source + ": expected section.key=value");
  const std::string name(trim(assignment.substr(0, eq)));
  std::string_view text = trim(assignment.substr(eq + 1));
  const Key* key = schema_->find(name);
  if (!key) throw InputError(source + ": " + unknown_key_message(*schema_, name));
  const std::string head = source + ": key '" + name + "' = '" + std::string(text) + "': ";
  if (std::holds_alternative<std::string>(key->default_value) && text.size() >= 2 && text.front() == '"' &&
      text.back() == '"')
    text = text.substr(1, text.size() - 2);
  Value value = std::visit([&](const auto& d) -> Value { return parse_set_value(d, *key, text, head); }, key->default_value);
  assign(*key, std::move(value), source, "'" + std::string(text) + "'");
}

template <class T>
const T& Config::get(std::string_view key) const {
  auto it = values_.find(key);
  if (it == values_.end()) throw std::logic_error("config key '" + std::string(key) + "' is not in the schema");
  if (const T* v = std::get_if<T>(&it->second)) return *v;
  throw std::logic_error("config key '" + std::string(key) + "' read as " + kind_name<T>());
}

std::int64_t Config::integer(std::string_view key) const { return get<std::int64_t>(key); }
double Config::real(std::string_view key) const { return get<double>(key); }
bool Config::boolean(std::string_view key) const { return get<bool>(key); }
const std::string& Config::string(std::string_view key) const { return get<std::string>(key); }
const RealList& Config::reals(std::string_view key) const { return get<RealList>(key); }
const StringList& Config::strings(std::string_view key) const { return get<StringList>(key); }

std::string Config::to_toml() const {
  std::string out = "# " + schema_->title + "\n";
  std::string section;
  for (const auto& k : schema_->keys) {
    auto dot = k.name.find('.');
    std::string s = k.name.substr(0, dot);
    if (s != section) {
      out += "\n[" + s + "]\n";
      section = s;
    }
    out += "# " + k.help + "\n";
    const Value& v = values_.at(k.name);
    out += k.name.substr(dot + 1) + " = " +
           (std::holds_alternative<RealList>(v) ? format_list(std::get<RealList>(v), k.group) : format_value(v)) + "\n";
  }
  return out;
}

}  // namespace clatter::io
