#pragma once
#include <string>

#include "io/h5.hpp"

namespace clatter::io {

// Stamps an output file: "/" gets the format name and version (what a reader checks first);
// group /provenance gets what produced it (command line, effective config as TOML, build info,
// rank count) and, kept apart from the content, the creation time (created_utc).
// Collective on a parallel file.
void write_header(File& file, const std::string& format, int format_version);
void write_provenance(File& file, const std::string& command_line, const std::string& config_toml, int n_ranks);

// Checks a file's format name and version; InputError naming the file otherwise.
void check_header(const File& file, const std::string& format, int format_version);

}  // namespace clatter::io
