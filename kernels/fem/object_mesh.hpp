#pragma once
// Quadratic (10-node) tetrahedral meshes of the solid any closed triangle mesh bounds, for the
// object bank's FEM (issue 29): the ellipsoid mesher's output (kernels/fem/ellipsoid_mesh.hpp)
// for a shape given as an OBJ.
//
// The steps (object_mesh.cpp): the input is checked (kernels/fem/mesh_check.hpp); a smooth surface
// is reconstructed through it where it is smooth (kernels/fem/smooth_surface.hpp: PN patches,
// sharp edges straight); its triangles are bisected (longest edge first) down to the local size,
// then improved by flips, merging and smoothing (object_refine.cpp), every point on the smooth
// surface; TetGen fills it, keeping that surface ("pYq<r>/<d>a<v>Q"); every boundary mid-node goes
// on the smooth surface (the chord's midpoint projected), so the boundary is curved where the
// input is smooth and flat where it is not; interior mid-nodes stay at their straight midpoints.
// A curved element that folds (a "cap" on two boundary faces) gets a point under it and TetGen
// runs again, up to four rounds.
//
// Sizing: h = min(edge_length_m, T / elements_through_thickness), T the local thickness (inward
// rays from the input's triangles, kernels/fem/smooth_surface.hpp), so a plate or a disk has about
// elements_through_thickness elements across while its bulk keeps edge_length_m.
#include <array>
#include <cstdint>
#include <vector>

#include "kernels/fem/assembly.hpp"
#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/fem/mesh_quality.hpp"

namespace clatter::kernels::fem {

struct ObjectMeshSettings {
  double edge_length_m = 0;            // target h in the bulk, > 0
  int elements_through_thickness = 3;  // at least this many edges across the local thickness
  double smooth_dihedral_deg = 30;     // faces whose normals differ by less: one smooth surface; 0: all flat
  double max_radius_edge = 1.5;        // TetGen's -q bounds, as the ellipsoid mesher's
  double min_dihedral_deg = 12.0;
  std::int64_t max_surface_triangles = 4'000'000;  // refuse (MeshError) sizes that would refine past this
  int retries = 2;  // a mesh that breaks the bounds is made again with every size times 0.8, this many times
};

struct ObjectMesh {
  Tet10Mesh mesh;                      // elements positively oriented (det J > 0)
  std::vector<BoundaryFace> boundary;  // as EllipsoidMesh's: vertices CCW from outside, then mid-nodes 01, 12, 20
  MeshQuality quality;                 // quality.edge_length_m: the smallest target size used
  double min_thickness_m = 0;          // the smallest thickness the inward rays found
  std::int64_t curved_edges = 0;       // boundary edges whose mid-node left the chord
  std::int64_t sharp_edges = 0;        // boundary edges along a sharp edge of the input
};

// Throws SurfaceError (kernels/fem/mesh_check.hpp, std::invalid_argument) for a surface that
// cannot bound one solid, std::invalid_argument for bad settings, MeshError("object mesh: ...")
// when TetGen fails or every try breaks `bounds`. Deterministic: the same input gives a
// bit-identical mesh.
ObjectMesh mesh_object(const std::vector<std::array<double, 3>>& vertices_m,
                       const std::vector<std::array<int, 3>>& triangles, const ObjectMeshSettings& settings,
                       const EllipsoidMeshBounds& bounds = {});

}  // namespace clatter::kernels::fem
