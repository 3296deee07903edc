#pragma once
// A smooth surface through a closed triangle mesh where the mesh is smooth enough to say so: per
// triangle the cubic PN patch of Vlachos et al. (2001, "Curved PN triangles"), built from the
// vertex positions and normals alone, so two triangles agree along their shared edge (the
// surface is continuous). An edge is sharp where its two faces' normals differ by more than
// smooth_dihedral_deg (mesh_contact's 30-degree rule by default): it stays straight, and a vertex
// takes one normal per smooth sector between its sharp edges, so a box comes back exactly flat and
// a disk's rim stays a polygon. Where every normal agrees the patch is the flat triangle itself.
#include <array>
#include <cstdint>
#include <vector>

namespace clatter::kernels::fem {

class SmoothSurface {
 public:
  // vertices and triangles as mesh_object takes them (closed, outward, checked).
  SmoothSurface(const std::vector<std::array<double, 3>>& vertices_m, const std::vector<std::array<int, 3>>& triangles,
                double smooth_dihedral_deg);

  // The point of triangle t's patch at barycentric coordinates (weights of its corners 0, 1, 2).
  std::array<double, 3> point(int t, const std::array<double, 3>& barycentric) const;
  // Edge k of triangle t (corners k, k+1) is sharp: straight.
  bool sharp(int t, int k) const { return sharp_[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)]; }
  std::int64_t sharp_edge_count() const { return sharp_edges_; }
  std::int64_t edge_count() const { return edges_; }

 private:
  std::vector<std::array<std::array<double, 3>, 10>> control_m_;  // b300 b030 b003 b210 b120 b021 b012 b102 b201 b111
  std::vector<std::array<bool, 3>> sharp_;
  std::int64_t sharp_edges_ = 0, edges_ = 0;
};

// Points onto the smooth surface: x goes to its foot (nearest point) on the patch of the input
// triangle it lies over, found by walking from a nearby triangle across the edge x lies beyond.
// Points on a flat patch or a straight (sharp) edge stay where they are.
class SurfaceProjector {
 public:
  SurfaceProjector(const std::vector<std::array<double, 3>>& vertices_m,
                   const std::vector<std::array<int, 3>>& triangles, const SmoothSurface& surface);
  // `triangle`: where the walk starts; on return, the triangle x went to.
  std::array<double, 3> project(const std::array<double, 3>& x_m, int& triangle) const;
  const SmoothSurface& surface() const { return surface_; }

 private:
  std::array<double, 3> foot(int t, const std::array<double, 3>& x_m) const;
  const std::vector<std::array<double, 3>>& vertices_;
  const std::vector<std::array<int, 3>>& triangles_;
  const SmoothSurface& surface_;
  std::vector<std::array<int, 3>> across_;  // the triangle across edge k (corners k, k+1)
};

// The body's thickness under each triangle: the distance from its centroid, along the inward
// normal, to the nearest other triangle the ray meets (a bounding-volume tree: n log n).
// A point inside the cavity each given triangle faces: halfway along the ray from its centroid
// along its normal (into the cavity: its triangles are wound inward) to the far wall.
std::vector<std::array<double, 3>> points_in_cavities_m(const std::vector<std::array<double, 3>>& vertices_m,
                                                        const std::vector<std::array<int, 3>>& triangles,
                                                        const std::vector<int>& facing);

std::vector<double> thickness_under_triangles_m(const std::vector<std::array<double, 3>>& vertices_m,
                                                const std::vector<std::array<int, 3>>& triangles);

}  // namespace clatter::kernels::fem
