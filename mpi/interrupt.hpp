#pragma once
// The collective side of core/interrupt.hpp: a SIGTERM/SIGINT seen by any rank stops every rank of
// a communicator at the same point, so nobody leaves a partial output or waits in a collective.
#include <mpi.h>

#include <string_view>

namespace clatter::mpi {

// Collective: true on every rank of `comm` when any rank has been asked to stop.
bool interrupt_seen(MPI_Comm comm);

// Collective: throws Interrupted("interrupted before WHERE") on every rank of `comm` when any rank
// has been asked to stop.
void poll_interrupt(MPI_Comm comm, std::string_view where);

}  // namespace clatter::mpi
