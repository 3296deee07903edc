#include "banks/medium_keys.hpp"

namespace clatter::jobs {

std::vector<io::Key> medium_and_pulse_keys() {
  return {
      {"medium.c_m_s", 343.2, "speed of sound [m/s]", {0.0, 1e5, true}},
      {"medium.rho_kg_m3", 1.2041, "density of the medium [kg/m^3]", {0.0, 1e5, true}},
      {"pulse.h_s", 1e-4, "width h of the acceleration pulse psi(t; h), support [-2h, 2h] [s]", {0.0, 1.0, true}},
  };
}

}  // namespace clatter::jobs
