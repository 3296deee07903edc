#pragma once
#include <mpi.h>

#include <string>

#include "core/stage_log.hpp"

namespace clatter::mpi {

// Collective over `comm`: gathers every rank's stage log and returns the -log_view-like table on
// rank 0 (an empty string elsewhere).
std::string stage_table(MPI_Comm comm, const StageLog& log);

}  // namespace clatter::mpi
