#pragma once
// Reading a whole text input (config, scene, sweep manifest) with the error every reader gives.
#include <fstream>
#include <sstream>
#include <string>

#include "core/errors.hpp"

namespace clatter::io {

// The file's bytes; InputError "PATH: cannot open WHAT" (or read) when it cannot be had.
inline std::string read_text_file(const std::string& path, const std::string& what = "config file") {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read " + what);
  return text.str();
}

}  // namespace clatter::io
