#pragma once
// `clatter-bank ground`: the ground bank as a sweep (jobs/bank_sweep.hpp) with one task per
// (ground material, listener elevation), merged into one bank file (io/ground_bank.hpp).
#include "io/config.hpp"
#include "jobs/bank_sweep.hpp"

namespace clatter::jobs {

// The ground bank's part of a sweep, from its config (validated here: InputError).
BankSweep ground_bank_sweep(const io::Config& config);

}  // namespace clatter::jobs
