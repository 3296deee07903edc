#pragma once
// The acoustic transfer stage of a modal bank entry (docs/transfer.md): after the eigensolve,
// every mode's exterior problem is solved (kernels/transfer/mode_transfer.hpp) with the modes
// dealt round-robin over the ranks of the entry's group. A mode's solve is serial and depends on
// nothing but its own data, so the stored transfer is bit-identical for any group size.
#include <mpi.h>

#include "kernels/transfer/mode_transfer.hpp"
#include "model/modal_bank.hpp"

namespace clatter::jobs {

// entry: complete on rank 0 of `group` (surface, shapes, frequencies), ignored elsewhere; on
// rank 0 its `transfer` and cost.transfer_s / transfer_core_s are filled in. settings: the bank
// header's (model::ModalBankHeader::transfer), which the kernel takes as they are.
void compute_modal_transfer(MPI_Comm group, const model::TransferSettings& settings, model::ModalEntry& entry);

// One mode of an entry, serially (what each rank runs; tests and `probe` use it too).
kernels::transfer::ModeTransfer mode_transfer(const model::ModalEntry& entry, std::size_t mode,
                                              const kernels::transfer::TransferSettings& settings);

}  // namespace clatter::jobs
