#pragma once
// Mass properties of a uniform solid bounded by a closed triangle mesh. By the divergence theorem
// the solid's integrals are sums over its faces: each triangle and one reference point span a
// tetrahedron whose signed volume and first and second moments are exact polynomials of its
// corners, so the result is exact for the polyhedron (up to rounding), convex or not.
#include <array>
#include <vector>

#include "kernels/rigid_body.hpp"

namespace clatter::kernels {

struct MeshMassProperties {
  // Signed: > 0 when the triangles wind counter-clockwise seen from outside (normals outward).
  double volume_m3 = 0;
  Vec3 centroid_m{};
  // Inertia tensor about the centroid of the solid at unit density [m^5]; times the density it is
  // kg m^2.
  Mat3 inertia_per_density_m5{};
  double surface_area_m2 = 0;  // the sum of the triangles' areas
};

// Triangles index into vertices; the mesh must be closed and consistently oriented for the result
// to mean anything (io/mesh checks that).
MeshMassProperties mesh_mass_properties(const std::vector<Vec3>& vertices_m,
                                        const std::vector<std::array<int, 3>>& triangles);

}  // namespace clatter::kernels
