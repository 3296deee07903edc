#pragma once
// Reading a ground bank back: `clatter-bank info` on a ground bank (serial work, rank 0 prints).
#include <string>

namespace clatter::jobs {

// A summary: the air, one line per material (moduli, wave speeds, the grid, the samples of Pi
// and their t_hat span), size, provenance, the sweep. Reads (and so checks) the whole bank; throws
// InputError.
std::string ground_bank_info(const std::string& path);

}  // namespace clatter::jobs
