#include "sim/voronoi.hpp"

#include <fmt/format.h>

#include <cmath>
#include <algorithm>
#include <memory>
#include <stdexcept>
#include <voro++/voro++.hh>

namespace clatter::sim {
namespace {


// One voro++ cell as a closed mesh: each face a convex polygon, fanned into triangles and turned to
// face outward (voro++ does not promise an orientation); its shared faces give the fracture centroid.
Piece cell_piece(voro::voronoicell_neighbor& cell, const Vec3& seed) {
  Piece p;
  std::vector<double> xyz;
  std::vector<int> faces, neighbours;
  cell.vertices(seed[0], seed[1], seed[2], xyz);
  cell.face_vertices(faces);
  cell.neighbors(neighbours);
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) p.vertices_m.push_back({xyz[i], xyz[i + 1], xyz[i + 2]});
  Vec3 centre{};
  for (const Vec3& v : p.vertices_m)
    for (int k = 0; k < 3; ++k) centre[k] += v[k] / static_cast<double>(p.vertices_m.size());
  Vec3 weighted{};
  std::size_t face = 0;
  for (std::size_t i = 0; i < faces.size(); i += static_cast<std::size_t>(faces[i]) + 1, ++face) {
    const int n = faces[i];
    std::vector<int> loop(faces.begin() + static_cast<std::ptrdiff_t>(i) + 1, faces.begin() + static_cast<std::ptrdiff_t>(i) + 1 + n);
    // Newell's normal of the polygon against the direction from the cell's centre.
    Vec3 normal{}, mid{};
    for (int k = 0; k < n; ++k) {
      const Vec3& a = p.vertices_m[loop[k]];
      const Vec3& b = p.vertices_m[loop[(k + 1) % n]];
      normal = {normal[0] + (a[1] - b[1]) * (a[2] + b[2]), normal[1] + (a[2] - b[2]) * (a[0] + b[0]),
                normal[2] + (a[0] - b[0]) * (a[1] + b[1])};
      for (int d = 0; d < 3; ++d) mid[d] += a[d] / n;
    }
    if (dot(normal, sub(mid, centre)) < 0) std::reverse(loop.begin(), loop.end());
    for (int k = 1; k + 1 < n; ++k) {
      p.triangles.push_back({loop[0], loop[k], loop[k + 1]});
      // Walls have negative ids; another cell's face is where the solid broke.
      if (face < neighbours.size() && neighbours[face] >= 0) {
        const Vec3 &a = p.vertices_m[loop[0]], &b = p.vertices_m[loop[k]], &c = p.vertices_m[loop[k + 1]];
        const Vec3 x = cross(sub(b, a), sub(c, a));
        const double area = 0.5 * std::sqrt(dot(x, x));
        for (int d = 0; d < 3; ++d) weighted[d] += area * (a[d] + b[d] + c[d]) / 3;
        p.fracture_area_m2 += area;
      }
    }
  }
  if (p.fracture_area_m2 > 0)
    for (int d = 0; d < 3; ++d) p.fracture_centroid_m[d] = weighted[d] / p.fracture_area_m2;
  else
    p.fracture_centroid_m = centre;
  return p;
}

}  // namespace

std::vector<Piece> voronoi_pieces(const Vec3& lo, const Vec3& hi, const std::vector<HalfSpace>& planes,
                                  const std::vector<Vec3>& seeds) {
  // About 5 seeds per block of voro++'s search grid.
  const int blocks = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(seeds.size()) / 5.0)));
  voro::container con(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], blocks, blocks, blocks, false, false, false, 8);
  std::vector<std::unique_ptr<voro::wall_plane>> walls;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    walls.push_back(std::make_unique<voro::wall_plane>(planes[i].normal[0], planes[i].normal[1], planes[i].normal[2],
                                                       planes[i].offset_m, -7 - static_cast<int>(i)));
    con.add_wall(*walls.back());
  }
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const Vec3& s = seeds[i];
    if (!con.point_inside(s[0], s[1], s[2]))
      throw std::invalid_argument(fmt::format("voronoi_pieces: seed {} ({}, {}, {}) lies outside the solid", i, s[0], s[1], s[2]));
    con.put(static_cast<int>(i), s[0], s[1], s[2]);
  }
  std::vector<Piece> pieces(seeds.size());
  std::vector<bool> done(seeds.size(), false);
  voro::c_loop_all loop(con);
  voro::voronoicell_neighbor cell;
  if (loop.start()) do {
      if (!con.compute_cell(cell, loop)) continue;
      const auto id = static_cast<std::size_t>(loop.pid());
      pieces[id] = cell_piece(cell, seeds[id]);
      done[id] = true;
    } while (loop.inc());
  for (std::size_t i = 0; i < seeds.size(); ++i)
    if (!done[i]) throw std::runtime_error(fmt::format("voronoi_pieces: voro++ computed no cell for seed {}", i));
  return pieces;
}

Uniform::Uniform(std::uint64_t seed) {
  for (auto& s : state_) {
    seed += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = seed;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    s = z ^ (z >> 31);
  }
}

std::uint64_t Uniform::next() {
  std::uint64_t s1 = state_[0];
  const std::uint64_t s0 = state_[1];
  state_[0] = s0;
  s1 ^= s1 << 23;
  state_[1] = s1 ^ s0 ^ (s1 >> 17) ^ (s0 >> 26);
  return state_[1] + s0;
}

double Uniform::operator()() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

}  // namespace clatter::sim
