#include "mpi/interrupt.hpp"

#include <string>

#include "core/errors.hpp"
#include "core/interrupt.hpp"
#include "mpi/collectives.hpp"

namespace clatter::mpi {

bool interrupt_seen(MPI_Comm comm) { return any(comm, interrupt_requested()); }

void poll_interrupt(MPI_Comm comm, std::string_view where) {
  if (interrupt_seen(comm)) throw Interrupted("interrupted before " + std::string(where));
}

}  // namespace clatter::mpi
