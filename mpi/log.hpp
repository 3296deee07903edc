#pragma once
#include <string>

namespace clatter::mpi {

// Rank-aware logging through spdlog's default logger. By default only rank 0 speaks; with
// all_ranks every rank does, each line tagged "[rank r/n]". Errors that end a run are printed by
// run() (session.hpp), not through the logger.
struct LogOptions {
  bool all_ranks = false;
  std::string level = "info";  // error, warn, info, debug
};

// Throws InputError for an unknown level.
void configure_logging(int rank, int size, const LogOptions& options);

}  // namespace clatter::mpi
