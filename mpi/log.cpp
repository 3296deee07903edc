#include "mpi/log.hpp"

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"

namespace clatter::mpi {

void configure_logging(int rank, int size, const LogOptions& options) {
  auto level = spdlog::level::from_str(options.level);
  if (options.level != "error" && options.level != "warn" && options.level != "info" && options.level != "debug")
    throw InputError("--log-level '" + options.level + "': expected one of error, warn, info, debug");
  spdlog::drop("clatter");  // configuring twice (tests) replaces the logger
  auto logger = spdlog::stdout_logger_mt("clatter");
  if (options.all_ranks && size > 1)
    logger->set_pattern("%H:%M:%S [rank " + std::to_string(rank) + "/" + std::to_string(size) + "] %l: %v");
  else
    logger->set_pattern("%H:%M:%S %l: %v");
  logger->set_level(rank == 0 || options.all_ranks ? level : spdlog::level::off);
  logger->flush_on(spdlog::level::trace);  // progress lines must appear as they happen under srun
  spdlog::set_default_logger(logger);
}

}  // namespace clatter::mpi
