#pragma once
// The object mesher's surface refinement (object_refine.cpp; internal to kernels/fem/object_*.cpp).
#include <array>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "kernels/fem/smooth_surface.hpp"

namespace clatter::kernels::fem {

std::int64_t undirected_edge_key(int a, int b);

// The input's triangles cut into facets with their points on the smooth surface; each facet
// remembers an input triangle near it (where projections from it start).
struct RefinedSurface {
  std::vector<std::array<double, 3>> points_m;
  std::vector<double> size_m;  // target edge length at each point
  std::vector<std::array<int, 3>> facets;
  std::vector<int> near_triangle;
  std::unordered_set<std::int64_t> sharp_edges;  // facet edges along the input's sharp edges (undirected_edge_key)
  std::vector<std::array<double, 3>> holes_m;    // a point in each cavity, for TetGen
};

// Rivara's longest-edge bisection (an edge is cut only once it is the longest of both its facets,
// so angles stay bounded below by the input's) until no edge is longer than the mean of its ends'
// sizes, the new points projected onto the smooth surface; then Delaunay flips, points closer than
// a third of their size merged and points smoothed towards their neighbours' mean (off the sharp
// edges), which clears the rows of points the bisection of long thin input triangles leaves.
// Throws MeshError past max_facets.
RefinedSurface refine_surface(const std::vector<std::array<double, 3>>& vertices_m,
                              const std::vector<std::array<int, 3>>& triangles, const SurfaceProjector& projector,
                              const std::vector<double>& vertex_size_m, std::int64_t max_facets);

}  // namespace clatter::kernels::fem
