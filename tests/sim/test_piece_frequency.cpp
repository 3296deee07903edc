// The base frequency clatter-sim writes for a thin fracture piece, against plate theory.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/piece_frequency.hpp"

namespace clatter::sim {
namespace {

// A free square plate's lowest mode (the twisting mode) has omega a^2 sqrt(rho h / D) = 13.468 for
// nu = 0.3 (Leissa, Vibration of Plates, NASA SP-160, Table 4.84), D = E h^3 / (12 (1 - nu^2)). A
// 40 x 40 x 0.4 cm piece (h / a = 0.01: thin-plate theory within a fraction of a per cent) given
// as its 8 corners and points on its faces, as a fracture surface is: the hull's grid must not
// flatten it (a grid of 1 % of the diagonal, 5.7 mm, did: its hull was non-manifold and the piece
// got no frequency).
TEST(PieceFrequency, ThinSquarePieceRingsAsAFreePlate) {
  const double a = 0.4, h = 0.004;
  model::Material steel;
  steel.youngs_pa = 200e9;
  steel.poisson = 0.3;
  steel.rho_kg_m3 = 7800;
  std::vector<Vec3> surface;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (double z : {-h / 2, h / 2}) surface.push_back({a * (i / 10.0 - 0.5), a * (j / 10.0 - 0.5), z});
  const double f_hz = piece_base_frequency_hz(surface, a * a * h, steel);
  const double d = steel.youngs_pa * h * h * h / (12 * (1 - 0.09));
  const double plate_hz = 13.468 / (2 * std::numbers::pi * a * a) * std::sqrt(d / (steel.rho_kg_m3 * h));
  std::printf("thin square piece: %.2f Hz, plate theory %.2f Hz (%+.2f %%)\n", f_hz, plate_hz, 100 * (f_hz / plate_hz - 1));
  EXPECT_NEAR(f_hz / plate_hz, 1.0, 0.03);
}

}  // namespace
}  // namespace clatter::sim
