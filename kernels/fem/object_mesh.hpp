#pragma once
// TEMPORARY STUB (replaced by the object mesher): straight 10-node mesh of a closed surface.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/fem/ellipsoid_mesh.hpp"

namespace clatter::kernels::fem {

struct ObjectMeshSettings {
  double edge_length_m = 0;
  int elements_through_thickness = 2;
};

struct ObjectMesh {
  Tet10Mesh mesh;
  std::vector<BoundaryFace> boundary;
  MeshQuality quality;
  double min_thickness_m = 0;
  std::int64_t curved_edges = 0, sharp_edges = 0;
};

ObjectMesh mesh_object(const std::vector<std::array<double, 3>>& vertices_m, const std::vector<std::array<int, 3>>& triangles,
                       const ObjectMeshSettings& settings, const EllipsoidMeshBounds& bounds = {});

std::string solid_mesh_problem(const std::vector<std::array<double, 3>>& vertices_m,
                               const std::vector<std::array<int, 3>>& triangles, double rho_kg_m3);

}  // namespace clatter::kernels::fem
