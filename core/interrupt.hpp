#pragma once
// SIGTERM and SIGINT as a request to stop cleanly. Slurm sends SIGTERM before the time limit
// (--signal) and on scancel; the handler only records the signal, and long loops poll it
// collectively (every rank of a group agrees before anyone stops), so no rank leaves a partial
// output behind or waits forever in a collective. A second SIGINT (Ctrl-C twice) kills at once.
namespace clatter {

void install_interrupt_handlers();  // idempotent
bool interrupt_requested() noexcept;
int interrupt_signal() noexcept;    // the signal number, 0 if none

}  // namespace clatter
