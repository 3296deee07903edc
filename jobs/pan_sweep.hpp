#pragma once
// `clatter-bank pan`: the PAN bank as a sweep (jobs/bank_sweep.hpp) of proxy x field tasks,
// merged into one bank file.
#include <mpi.h>

#include <string>

#include "io/config.hpp"
#include "jobs/bank_sweep.hpp"

namespace clatter::jobs {

// The PAN bank's part of a sweep, from its config (validated here: InputError).
BankSweep pan_bank_sweep(const io::Config& config, double progress_interval_s);

}  // namespace clatter::jobs
