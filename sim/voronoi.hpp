#pragma once
// Pre-fracture: a convex solid cut into the Voronoi cells of seed points (voro++), each cell a
// convex piece with its closed triangle mesh and the centroid of its fracture faces (the faces it
// shares with other cells, where the solid broke).
#include <array>
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"

namespace clatter::sim {

// A half-space n . x <= d (n a unit vector): the solid is the intersection of planes and a box.
struct HalfSpace {
  Vec3 normal{};
  double offset_m = 0;
};

struct Piece {
  std::vector<Vec3> vertices_m;               // the solid's coordinates
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
  Vec3 fracture_centroid_m{};                 // area-weighted centroid of its faces shared with other pieces
  double fracture_area_m2 = 0;
};

// The cells of `seeds` inside box [lo, hi] cut by `planes` (seeds outside the solid are an error),
// in the order of the seeds. Cells are exact convex polyhedra whose union is the solid.
std::vector<Piece> voronoi_pieces(const Vec3& lo, const Vec3& hi, const std::vector<HalfSpace>& planes,
                                  const std::vector<Vec3>& seeds);

// A deterministic stream of uniform numbers in [0, 1): xorshift128+ seeded by SplitMix64, both
// fixed integer recurrences, with our own conversion to double (std::uniform_real_distribution's
// is not specified), so the same seed gives the same pieces on every platform.
class Uniform {
 public:
  explicit Uniform(std::uint64_t seed);
  double operator()();

 private:
  std::array<std::uint64_t, 2> state_{};
  std::uint64_t next();
};

}  // namespace clatter::sim
