#pragma once
// One number token of a text input format (OBJ, James-lab impulses), read with strtod so that
// "nan" and "inf" are recognised and then refused by name.
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "core/errors.hpp"

namespace clatter::io {

// where: "FILE:LINE"; what: the quantity, for the message.
inline double finite_number(const std::string& token, const std::string& what, const std::string& where) {
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != 0) throw InputError(fmt::format("{}: {} '{}' is not a number", where, what, token));
  if (!std::isfinite(v)) throw InputError(fmt::format("{}: {} is {}: must be finite", where, what, token));
  return v;
}

}  // namespace clatter::io
