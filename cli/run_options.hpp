#pragma once
// What every clatter-bank subcommand shares: the config options (-c, --set, --print-config, -o),
// the global options (logging, timing, progress), and loading a config the same way on every rank.
#include <CLI/CLI.hpp>
#include <mpi.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "io/config.hpp"

namespace clatter::jobs {

// The options of a config-driven subcommand: -c/--config, --set and --print-config.
struct ConfigOptions {
  std::string config_path;        // empty: the built-in defaults
  std::vector<std::string> sets;  // "section.key=value", applied in order after the file
  bool print_config = false;      // print the effective config and exit
};

// Options of the program, given before or after the subcommand.
struct GlobalOptions {
  bool log_view = false;
  bool log_all_ranks = false;
  std::string log_level = "info";
  double progress_interval_s = 10;
};

void add_config_options(CLI::App& sub, ConfigOptions& options);
// -o/--out; `out` holds the default.
void add_out_option(CLI::App& sub, std::string& out, const std::string& help);
void add_global_options(CLI::App& app, GlobalOptions& options);

// A config a subcommand runs without -c/--config, built into the binary (ground: its demo grid).
struct BuiltinConfig {
  std::string toml;
  std::string source;  // names it in messages, e.g. "configs/ground-demo.toml (built in)"
};

// The schema's defaults < the -c file (or `builtin`, when no file is given) < --set. Rank 0 reads
// the file; every rank parses the same text, so a bad config fails identically everywhere (as a
// CollectiveError with exit code 2) and no rank is left waiting.
io::Config load_config(MPI_Comm comm, const io::Schema& schema, const ConfigOptions& options,
                       const BuiltinConfig* builtin = nullptr);
// The same, or nullopt when --print-config asked only to print it (rank 0 prints).
std::optional<io::Config> job_config(MPI_Comm comm, const io::Schema& schema, const ConfigOptions& options,
                                     const BuiltinConfig* builtin = nullptr);

// A subcommand that runs one config of `schema` into one output file (-c, --set, --print-config,
// -o): `run` gets the loaded config and the output path on every rank, unless --print-config.
using ConfigRun = std::function<void(const RunContext&, const io::Config& config, const std::string& out)>;
Command add_config_command(CLI::App& parent, const std::string& name, const std::string& help,
                           const io::Schema& schema, const std::string& default_out, const std::string& out_help,
                           ConfigRun run);

// The command line as one string, for provenance.
std::string command_line(int argc, char** argv);

// H:MM:SS, rounded up (ETAs and time limits).
std::string clock_text(double seconds);

}  // namespace clatter::jobs
