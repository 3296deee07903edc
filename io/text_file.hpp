#pragma once
// Reading a whole text input (config, scene, sweep manifest) with the error every reader gives, and
// writing a whole text output (a scene's meshes, clatter-synth's --voices) as every output is written.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/cleanup.hpp"
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

// `text` into `path` through PATH.partial and a rename: never a partial file under the name (the
// temporary is removed if the program is stopped). InputError when it cannot be created.
inline void write_text_file(const std::string& path, const std::string& text, const std::string& what) {
  const std::string temp = path + ".partial";
  register_temporary(temp);
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot create the " + what + " file");
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(path + ": writing the " + what + " failed (disk full?)");
  }
  std::filesystem::rename(temp, path);
  unregister_temporary(temp);
}

}  // namespace clatter::io
