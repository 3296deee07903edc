#pragma once
// An adaptive direction set of one PAN field (issue 32): the positive octant's six-node quadratic
// elements (directions.hpp) as roots, each split into four by its edge midpoints where the
// quadratic interpolation of its nodes misses the field. Vertices lie on a fine lattice of the
// gnomonic triangle x + y + z = 1, a point (a, b) being the direction (a, b, L - a - b) / |.|; the
// lattice has room for `max_levels` splits below a root, so every node of every element is a
// lattice point and a vertex shared by neighbours is stored once.
//
// The split of an element (corners P0, P1, P2; midpoints M01, M12, M20) gives the children
// (P0, M01, M20), (M01, P1, M12), (M20, M12, P2) and the centre (M12, M20, M01); barycentric
// coordinates are linear in the gnomonic plane, so a direction is located by descending from its
// root. A refined element's neighbour is not refined with it: along their shared edge the fine side
// interpolates through five nodes and the coarse side through three, both through the same stored
// values, so the interpolant may step there by at most what the refinement tolerates.
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "kernels/pan/directions.hpp"
#include "model/pan_bank.hpp"

namespace clatter::kernels::pan {

using model::LatticePoint;
inline std::int64_t lattice_key(const LatticePoint& p) {  // for maps
  return (static_cast<std::int64_t>(p.a) << 32) | static_cast<std::uint32_t>(p.b);
}

class DirectionMesh {
 public:
  // The uniform layout of `divisions` (even; 8: the paper's 45 directions), unrefined, on a
  // lattice with room for `max_levels` splits. Its vertices are direction_vertices(divisions), in
  // that order, and locate() gives locate_direction's quadratic weights.
  DirectionMesh(int divisions, int max_levels);
  // A stored set (a bank's): throws std::invalid_argument unless its arrays form a mesh of this
  // layout and lattice (roots first, children after their parent, every node the lattice point
  // its element implies).
  DirectionMesh(int divisions, int max_levels, const model::PanDirections& stored);

  int divisions() const { return divisions_; }
  int max_levels() const { return max_levels_; }
  int lattice() const { return lattice_; }
  // The arrays as a bank stores them.
  const model::PanDirections& stored() const { return set_; }
  std::size_t size() const { return set_.vertices.size(); }
  const std::vector<LatticePoint>& vertices() const { return set_.vertices; }
  // Nodes of each element: corners 0-2, then the midpoints of edges 01, 12, 20.
  const std::vector<std::array<std::int32_t, 6>>& elements() const { return set_.elements; }
  // Per element, the first of its four children (consecutive), or -1 for a leaf.
  const std::vector<std::int32_t>& first_child() const { return set_.first_child; }
  std::array<double, 3> direction(std::size_t vertex) const { return direction(set_.vertices.at(vertex)); }
  std::array<double, 3> direction(const LatticePoint& p) const;
  int level(std::size_t element) const { return level_.at(element); }

  // The nine lattice points a split of element e would add (the children's edge midpoints), each
  // with its barycentric coordinates in e.
  struct SplitPoint {
    LatticePoint point;
    std::array<double, 3> l;
  };
  std::array<SplitPoint, 9> split_points(std::size_t element) const;
  bool can_split(std::size_t element) const { return set_.first_child.at(element) < 0 && level_.at(element) < max_levels_; }
  // Splits a leaf; the new vertices are appended (their indices from the old size() on).
  void split(std::size_t element);

  // Quadratic weights over the leaf holding direction d (closed positive octant).
  DirectionWeights locate(const std::array<double, 3>& d) const;  // pan::locate(divisions(), stored(), d)
  // The six nodes' weights at barycentric coordinates l of element e.
  DirectionWeights weights(std::size_t element, const std::array<double, 3>& l) const;

 private:
  int vertex_at(const LatticePoint& p);  // existing or appended
  int divisions_, max_levels_, lattice_;
  model::PanDirections set_;
  std::vector<int> level_;
  std::unordered_map<std::int64_t, int> index_;  // lattice point -> vertex
};

// The uniform layout of `divisions` (2 times a power of two; 8: the paper's 45 directions) as the
// two-division root split uniformly, with room for `extra_levels` more splits. The same directions
// and the same quadratic elements as DirectionMesh(divisions, extra_levels), numbered from the
// root down: a bank stores every direction below the root against its parent (io/pan_bank.cpp).
DirectionMesh uniform_mesh(int divisions, int extra_levels);

// Splits elements, coarsest first, while some split point misses by more than `tolerance`:
// miss(point, w) is how far the interpolation with weights w over the mesh's vertices (the
// caller's values at mesh.direction(v)) misses the true value at mesh.direction(point), in the
// caller's measure. Stops at max_levels or after `max_vertices` vertices. Returns the splits made.
// `ahead`, if given, is told each element's split points before their misses are asked, so that a
// caller can get their true values together (kernels/fdtd/kirchhoff.hpp hears several directions
// in one pass).
using DirectionMiss = std::function<double(const LatticePoint& point, const DirectionWeights& w)>;
using DirectionsAhead = std::function<void(const std::vector<LatticePoint>& points)>;

// out = sum_k w.weight[k] series(w.vertex[k]): a per-vertex series interpolated at a direction.
// `series` maps a vertex index to its samples (all of out.size()).
template <class SeriesOf>
void blend(const DirectionWeights& w, SeriesOf&& series, std::vector<double>& out) {
  std::fill(out.begin(), out.end(), 0.0);
  for (int k = 0; k < w.count; ++k) {
    const auto& s = series(static_cast<std::size_t>(w.vertex[static_cast<std::size_t>(k)]));
    for (std::size_t n = 0; n < out.size(); ++n) out[n] += w.weight[static_cast<std::size_t>(k)] * s[n];
  }
}
int refine(DirectionMesh& mesh, const DirectionMiss& miss, double tolerance, std::size_t max_vertices,
           const DirectionsAhead& ahead = {});

// Weights at direction d (closed positive octant) over the leaf of `set` that holds it: quadratic
// over the leaf's six nodes, or linear over the one of its four triangles (corner and midpoints)
// that holds d; unrefined, locate_direction's. `set` is a mesh of the layout of `divisions` whose
// indices are in range (a DirectionMesh's, or a bank's as io::read_pan_bank checks it); the
// evaluator locates in a bank's sets in place, with no mesh built.
DirectionWeights locate(int divisions, const model::PanDirections& set, const std::array<double, 3>& d,
                        Interpolation interpolation = Interpolation::quadratic);

}  // namespace clatter::kernels::pan
