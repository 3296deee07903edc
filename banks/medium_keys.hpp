#pragma once
// Schema keys every acoustic job shares. Apart from cli/run_options.hpp (CLI11, MPI), so the
// MPI-free specs (clatter_specs) can build their schemas from them.
#include <vector>

#include "io/config.hpp"

namespace clatter::jobs {

// medium.c_m_s, medium.rho_kg_m3, pulse.h_s.
std::vector<io::Key> medium_and_pulse_keys();

}  // namespace clatter::jobs
