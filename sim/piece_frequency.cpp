#include "sim/piece_frequency.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

#include "kernels/fem/lowest_mode.hpp"
#include "sim/world.hpp"

namespace clatter::sim {

double piece_base_frequency_hz(const std::vector<Vec3>& surface_m, double volume_m3, const model::Material& material) {
  Vec3 lo = surface_m.front(), hi = lo;
  for (const Vec3& x : surface_m)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
  const double cell = 0.05 * std::min({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  std::set<std::array<long long, 3>> seen;
  std::vector<Vec3> snapped;
  for (const Vec3& x : surface_m) {
    const std::array<long long, 3> key{std::llround(x[0] / cell), std::llround(x[1] / cell), std::llround(x[2] / cell)};
    if (seen.insert(key).second)
      snapped.push_back({static_cast<double>(key[0]) * cell, static_cast<double>(key[1]) * cell, static_cast<double>(key[2]) * cell});
  }
  const io::TriangleMesh hull = convex_hull(snapped, 32);
  kernels::fem::LowestModeSettings quick;
  quick.edge_length_m = std::cbrt(volume_m3);  // 10-node elements: a few through the piece suffice
  quick.tolerance = 1e-6;                      // the frequency to about 1e-6, far below the hull's error
  quick.max_iterations = 1000;
  try {
    return kernels::fem::lowest_free_mode(hull.vertices_m, hull.triangles, material.youngs_pa, material.poisson, material.rho_kg_m3, quick)
        .frequency_hz;
  } catch (const std::exception&) {
    return 0;
  }
}

}  // namespace clatter::sim
