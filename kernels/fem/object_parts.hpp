#pragma once
// The object mesher's surface refinement (object_refine.cpp; internal to kernels/fem/object_*.cpp).
#include <array>
#include <cstdint>
#include <vector>

#include "kernels/fem/smooth_surface.hpp"

namespace clatter::kernels::fem {

// The input's triangles cut into facets, each inside one input triangle (its source), its corners
// on the smooth surface at the given barycentric coordinates of the source.
struct RefinedSurface {
  std::vector<std::array<double, 3>> points_m;
  std::vector<double> size_m;  // target edge length at each point
  std::vector<std::array<int, 3>> facets;
  std::vector<int> source;
  std::vector<std::array<std::array<double, 3>, 3>> corner_barycentric;
};

// Rivara's longest-edge bisection (an edge is cut only once it is the longest of both its facets,
// so angles stay bounded below by the input's) until no edge is longer than the mean of its ends'
// sizes; the new point of an edge at its parameter midpoint on the smooth surface. Then Delaunay
// flips, and in flat regions points moved towards their neighbours' mean. Throws MeshError past max_facets.
RefinedSurface refine_surface(const std::vector<std::array<double, 3>>& vertices_m,
                              const std::vector<std::array<int, 3>>& triangles, const SmoothSurface& surface,
                              const std::vector<double>& vertex_size_m, std::int64_t max_facets);

}  // namespace clatter::kernels::fem
