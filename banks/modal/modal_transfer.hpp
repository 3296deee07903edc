#pragma once
// The acoustic transfer stage of a modal bank entry (docs/transfer.md): after the eigensolve,
// every mode's exterior problem is solved (kernels/transfer/mode_transfer.hpp), the modes handed
// out one at a time to whichever rank of the entry's group is free. A mode's solve is serial and
// depends on nothing but its own data, so the stored transfer is bit-identical for any group size
// and any order in which the ranks take the modes.
#include <mpi.h>

#include <functional>

#include "kernels/transfer/mode_transfer.hpp"
#include "model/modal_bank.hpp"

namespace clatter::jobs {

// One mode of an entry, serially: what each rank runs for the modes dealt to it.
using ModeTransferSolver = std::function<kernels::transfer::ModeTransfer(const model::ModalEntry& entry, std::size_t mode)>;

// entry: complete on rank 0 of `group` (surface, shapes, frequencies), ignored elsewhere; on
// rank 0 its `transfer` and cost.transfer_s / transfer_core_s are filled in. `solve` is the
// ellipsoid's mode_transfer below with the bank header's settings, or the object bank's solve for
// an arbitrary surface. A mode whose solve throws fails the task (TaskFailure, on every rank); an
// interrupt stops every rank once it has finished the mode it holds (Interrupted).
void compute_modal_transfer(MPI_Comm group, const ModeTransferSolver& solve, model::ModalEntry& entry);

// One mode of an entry, serially (what each rank runs; tests and `probe` use it too).
kernels::transfer::ModeTransfer mode_transfer(const model::ModalEntry& entry, std::size_t mode,
                                              const kernels::transfer::TransferSettings& settings);

}  // namespace clatter::jobs
