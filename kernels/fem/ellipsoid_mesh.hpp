#pragma once
// Quadratic (10-node) tetrahedral meshes of a solid ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 <= 1 for
// the modal bank's FEM (paper §5, Appendix E). The volume is tetrahedralised by TetGen from a
// closed triangulation of the surface; mid-nodes are added here: interior edges at their straight
// midpoints, boundary edges moved onto the ellipsoid, so the boundary faces are curved
// (isoparametric) and the boundary geometry error is O(h^3) instead of O(h^2).
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/fem/assembly.hpp"
#include "kernels/fem/mesh_quality.hpp"

namespace clatter::kernels::fem {

// The surface spacing follows the curvature: a surface edge of length L is cut while its mid-node
// moves onto the ellipsoid by more than k/8 min(L, 1.69 k T), T the chord through the body along
// the normal (the local thickness); that is L <= k R where the body is thick (R the curvature
// radius along the edge) and L <= 1.3 k sqrt(R T) where it is thin, and edges stay within 1.5 h.
// kernels/fem/surface_sizing.cpp argues the rule, tests/unit/test_ellipsoid_mesh.cpp measures it.
inline constexpr double kSpacingPerCurvatureRadius = 1.0;  // k

struct EllipsoidMeshSettings {
  std::array<double, 3> semi_axes_m{1, 1, 1};  // a, b, c
  double edge_length_m = 0.25;                 // target h; capped at (2 min axis) / elements_through_thickness
  // Quadratic elements through the thinnest axis: 10-node tetrahedra hold pure bending exactly, so
  // a plate needs few (docs/modal.md "Defaults and why" measures 1 to 3 on 1:33 ellipsoids).
  double elements_through_thickness = 3;
  double max_radius_edge = 1.5;                // TetGen's -q bound (circumradius / shortest edge)
  double min_dihedral_deg = 12.0;              // TetGen's -q bound on the smallest dihedral angle
  double spacing_per_curvature_radius = kSpacingPerCurvatureRadius;  // k above; scale it with h to refine all
};

// What a mesh must satisfy to be used; looser than the switches because TetGen cannot split the
// preserved surface (-Y), so tetrahedra touching it may miss the -q bounds.
struct EllipsoidMeshBounds {
  double max_radius_edge = 3.0;
  double min_dihedral_deg = 5.0;
  double min_jacobian_ratio = 0.2;  // min det J / max det J within each curved element
};

// A boundary face: 6 nodes (vertices 0-2 counter-clockwise seen from outside, then the mid-nodes
// of edges 01, 12, 20), indices into the mesh's nodes.
using BoundaryFace = std::array<int, 6>;

struct EllipsoidMesh {
  Tet10Mesh mesh;
  std::vector<BoundaryFace> boundary;
  MeshQuality quality;
};

// A mesh that could not be made, or failed the bounds: `what()` gives the reason.
class MeshError : public std::runtime_error {
 public:
  explicit MeshError(const std::string& reason) : std::runtime_error("ellipsoid mesh: " + reason) {}
  MeshError(const std::string& mesher, const std::string& reason) : std::runtime_error(mesher + ": " + reason) {}
};

// Deterministic: the same settings give a bit-identical mesh. Throws std::invalid_argument for
// non-positive axes, h or elements through the thickness, MeshError when TetGen fails or the mesh breaks `bounds`.
EllipsoidMesh mesh_ellipsoid(const EllipsoidMeshSettings& settings, const EllipsoidMeshBounds& bounds = {});

// A flat ellipsoid (the smallest semi-axis a a fraction of the middle one) in layers: its mid-plane
// ellipse triangulated (kernels/fem/ellipse_triangulation.hpp) with edges of edge_length_m in the
// bulk, graded to rim_edge_fraction of that at the rim; each triangle extruded through the local
// thickness 2 a sqrt(1 - rho^2) in `layers` prisms of 3 tetrahedra (the diagonals chosen by node
// number, so neighbours agree), the columns collapsing to one node on the rim. TetGen's isotropic
// fill needs h <= 2a / N everywhere and folds the thin rim below N = 3; here the in-plane h is
// free of the thickness, which quadratic elements resolve in one or two layers (docs/modal.md
// "Thin entries"). Only the Jacobian bound applies: the elements are flat on purpose.
struct LayeredMeshSettings {
  std::array<double, 3> semi_axes_m{0.1, 1, 1};
  double edge_length_m = 0.25;       // in-plane h in the bulk
  int layers = 2;                    // elements through the thickness
  // The rim: the thickness a sqrt(1 - rho^2) has infinite slope there, and an isotropic grading
  // that resolves it costs most of the mesh. A band of rim_rings rings instead, at depths 1 - rho
  // halving toward the rim, spaced rim_spacing_fraction h along it, the deepest where the rings'
  // radial step (along b) equals that spacing; inside it, h grows from that spacing by
  // rim_grading per unit distance (docs/modal.md "Thin entries" measures them against TetGen's).
  int rim_rings = 6;
  double rim_spacing_fraction = 0.5;
  double rim_grading = 0.3;
};
EllipsoidMesh mesh_layered_ellipsoid(const LayeredMeshSettings& settings, const EllipsoidMeshBounds& bounds = {});

// The closed surface triangulation handed to TetGen (vertices on the ellipsoid, faces outward):
// exposed for the tests.
struct SurfaceTriangulation {
  std::vector<std::array<double, 3>> vertices_m;
  std::vector<std::array<int, 3>> faces;
};
SurfaceTriangulation ellipsoid_surface(const std::array<double, 3>& semi_axes_m, double edge_length_m,
                                       double spacing_per_curvature_radius = kSpacingPerCurvatureRadius);

// The point of the ellipsoid on the ray from its centre through p (p != 0).
std::array<double, 3> onto_ellipsoid(const std::array<double, 3>& semi_axes_m, const std::array<double, 3>& p_m);

// The point of the ellipsoid nearest to p, which lies near it (closer than the curvature radius):
// where a mid-node goes. Unlike the ray from the centre, it moves a point along the normal only,
// which on a cigar's side is not the ray's direction.
std::array<double, 3> nearest_on_ellipsoid(const std::array<double, 3>& semi_axes_m, const std::array<double, 3>& p_m);

// The smallest principal curvature radius of the ellipsoid at x, a point on it.
double min_curvature_radius_m(const std::array<double, 3>& semi_axes_m, const std::array<double, 3>& x_m);

}  // namespace clatter::kernels::fem
