#pragma once
// What every clatter-bank subcommand shares: the config options (-c, --set, --print-config), the
// logging and timing options, and loading a config the same way on every rank.
#include <CLI/CLI.hpp>
#include <mpi.h>

#include <optional>
#include <string>
#include <vector>

#include "io/config.hpp"

namespace clatter::jobs {

// The options every config-driven job shares: -c/--config, --set, --print-config, -o/--out and,
// for long jobs, --progress-interval.
struct JobOptions {
  std::string config_path;        // empty: the built-in defaults
  std::vector<std::string> sets;  // "section.key=value", applied in order after the file
  bool print_config = false;      // print the effective config and exit
  std::string out;
  double progress_interval_s = 10.0;
};

struct GlobalOptions {
  bool log_view = false;
  bool log_all_ranks = false;
  std::string log_level = "info";
};

// Declares the shared options on `sub`; `out` starts as the default output. progress: also
// --progress-interval.
void add_job_options(CLI::App& sub, JobOptions& options, const char* out_help, bool progress);
void add_global_options(CLI::App& app, GlobalOptions& options);

// Rank 0 reads the file; every rank parses the same text, so a bad config fails identically
// everywhere (as a CollectiveError with exit code 2) and no rank is left waiting.
io::Config load_config(MPI_Comm comm, const io::Schema& schema, const JobOptions& options);
// The same, or nullopt when --print-config asked only to print it (rank 0 prints).
std::optional<io::Config> job_config(MPI_Comm comm, const io::Schema& schema, const JobOptions& options);

// The command line as one string, for provenance.
std::string command_line(int argc, char** argv);

// H:MM:SS, rounded up (ETAs and time limits).
std::string clock_text(double seconds);

}  // namespace clatter::jobs
