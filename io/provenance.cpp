#include "io/provenance.hpp"

#include <chrono>
#include <ctime>

#include "core/build_info.hpp"
#include "core/errors.hpp"
#include "io/linked_libraries.hpp"

namespace clatter::io {

void write_header(File& file, const std::string& format, int format_version) {
  write_attribute(file, "/", "format", format);
  write_attribute<std::int32_t>(file, "/", "format_version", format_version);
}

void write_provenance(File& file, const std::string& command_line, const std::string& config_toml, int n_ranks) {
  const BuildInfo& b = build_info();
  create_group(file, "/provenance");
  const std::string g = "/provenance";
  write_attribute(file, g, "config_toml", config_toml);
  write_attribute(file, g, "clatter_version", b.version);
  write_attribute(file, g, "git_revision", b.git_revision);
  write_attribute(file, g, "compiler", b.compiler);
  // The libraries the writing binary runs with: no "mpi" from a binary without MPI.
  if (const auto mpi = mpi_library()) write_attribute(file, g, "mpi", *mpi);
  write_attribute(file, g, "hdf5", hdf5_library());
  // How this copy was made rather than what it holds: the same content can come from 1 or 64
  // ranks, now or later. Content hashes (clatter-bank checksum) leave /provenance/run out.
  const std::string run = "/provenance/run";
  create_group(file, run);
  write_attribute(file, run, "command", command_line);
  write_attribute<std::int32_t>(file, run, "n_ranks", n_ranks);
  // Every rank must write the same bytes into a parallel file's attribute: the time comes from
  // rank 0 (seconds resolution, and ranks start together), broadcast to be safe.
  long long now = static_cast<long long>(std::time(nullptr));
  file.broadcast(&now, sizeof now);
  std::time_t t = static_cast<std::time_t>(now);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  write_attribute(file, run, "created_utc", std::string(text));
}

void check_header(const File& file, const std::string& format, int format_version) {
  std::string found;
  try {
    found = read_string_attribute(file, "/", "format");
  } catch (const InputError&) {
    throw InputError(file.path() + ": not a Clatter file (no 'format' attribute); expected format '" + format + "'");
  }
  if (found != format)
    throw InputError(file.path() + ": format '" + found + "', expected '" + format + "'");
  const auto version = read_attribute<std::int32_t>(file, "/", "format_version");
  if (version != format_version)
    throw InputError(file.path() + ": format '" + format + "' version " + std::to_string(version) +
                     ", this build reads version " + std::to_string(format_version));
}

}  // namespace clatter::io
