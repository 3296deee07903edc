#pragma once
// The ellipsoid mesher's parts that do not see TetGen (internal to kernels/fem/ellipsoid_*.cpp).
#include <array>
#include <functional>
#include <set>
#include <vector>

#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/fem/tetgen_fill.hpp"

namespace clatter::kernels::fem {

// The surface refinement's rule (surface_sizing.cpp, where it is argued): an edge is too coarse
// if longer than max_edge_m or if its sagitta exceeds k/8 min(L, 1.69 k T), T = normal_chord_m at
// its midpoint's nearest point on the ellipsoid. (refine_surface adds an isotropy condition.)
struct EdgeRule {
  std::array<double, 3> semi_axes_m;
  double max_edge_m;
  double k;
  bool too_coarse(const std::array<double, 3>& a_m, const std::array<double, 3>& b_m) const;
};

// The chord through the body from x (on the ellipsoid) along the inward normal.
double normal_chord_m(const std::array<double, 3>& semi_axes_m, const std::array<double, 3>& x_m);

// Bisects edges of `s` (vertices on the ellipsoid, faces outward) until no edge is too coarse;
// edges already fine enough are kept, so a surface that resolves its curvature (a sphere at
// h <= k R) comes back unchanged. True where it cut any. Throws MeshError if it does not end.
bool refine_surface(SurfaceTriangulation& s, const EdgeRule& rule);

// Bisects the given edges (vertex pairs; those not edges of `s` are ignored) and what the
// longest-edge rule then asks for.
void bisect_surface_edges(SurfaceTriangulation& s, const EdgeRule& rule, const std::vector<std::array<int, 2>>& edges);

// The rule ellipsoid_surface refines to (ellipsoid_surface.cpp).
EdgeRule surface_rule(const std::array<double, 3>& semi_axes_m, double edge_length_m, double spacing_per_curvature_radius);

// Edge flips and smoothing that raise the triangles' smallest angles (surface_improve.cpp); the
// smoothing turns no edge too coarse, a flip may (refine again after). The vertices stay on the
// ellipsoid and their count is kept.
void improve_surface(SurfaceTriangulation& s, const EdgeRule& rule);

// Flips the surface edge a-b to the other diagonal of its two faces' quadrilateral; false where
// that edge is there already (surface_improve.cpp).
bool flip_surface_edge(SurfaceTriangulation& s, int a, int b);

// ellipsoid_repair.cpp: a layer of points under the surface vertices (so TetGen leaves no "caps",
// tetrahedra on four surface vertices), and the repairs for a mesh's elements that break
// `bounds`: a flipped surface edge under a cap on two boundary faces, a point added under another
// folded element, a bisected surface edge under a badly shaped one, or one of our points taken
// out of a badly shaped one inside. False where it changed nothing (no element broke the bounds,
// or none it could repair).
std::vector<std::array<double, 3>> inner_layer(const SurfaceTriangulation& surface, const std::array<double, 3>& semi_axes_m);
struct MeshRepairs {
  std::vector<std::array<double, 3>> extra;   // added to the layer
  std::set<std::array<double, 3>> dropped;    // taken out of the layer and `extra`
};
// `inner`: the points handed to TetGen after the surface's (the mesh's nodes from n_surface on).
bool repair_mesh(const EllipsoidMesh& mesh, const EdgeRule& rule, const EllipsoidMeshBounds& bounds,
                 const std::vector<std::array<double, 3>>& inner, SurfaceTriangulation& surface, MeshRepairs& repairs);

// The 10-node mesh of a linear one whose first n_surface_points points are its surface vertices
// (on the ellipsoid): tetrahedra turned positive, the boundary found (faces met once, outward),
// mid-nodes at straight midpoints inside and on the ellipsoid (nearest point) on the boundary. Both
// meshers (TetGen's fill, ellipsoid_mesh.cpp; the layers of a flat body, layered_ellipsoid.cpp)
// end here.
EllipsoidMesh quadratic_mesh(LinearMesh& linear, const std::array<double, 3>& semi_axes_m, std::size_t n_surface_points);
// The same with the mid-node of edge a-b (vertex indices) where `place` puts it.
using MidNodePlacement = std::function<std::array<double, 3>(int a, int b, bool on_surface)>;
EllipsoidMesh quadratic_mesh(LinearMesh& linear, std::size_t n_surface_points, const MidNodePlacement& place);

// Throws MeshError naming the first bound the mesh's quality breaks.
void check_bounds(const MeshQuality& quality, const EllipsoidMeshBounds& bounds);

}  // namespace clatter::kernels::fem
