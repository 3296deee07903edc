#pragma once
// `clatter-bank modal`: the modal bank as a sweep (jobs/bank_sweep.hpp) with one task per patch
// sample, merged into one bank file (io/modal_bank.hpp).
#include "io/config.hpp"
#include "jobs/bank_sweep.hpp"

namespace clatter::jobs {

// The modal bank's part of a sweep, from its config (validated here: InputError).
BankSweep modal_bank_sweep(const io::Config& config);

}  // namespace clatter::jobs
