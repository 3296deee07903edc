#pragma once
// The linear tetrahedral mesh a breakable body is (003 section 3): the quasistatic stress solve
// (quasistatic.hpp), the fracture pattern (pattern.hpp) and the fracture impulses (impulses.hpp)
// all work on it, in the body's own coordinates (metres).
#include <array>
#include <vector>

#include "core/vec3.hpp"

namespace clatter::kernels::fracture {

using Mat3 = std::array<std::array<double, 3>, 3>;  // row-major

struct TetMesh {
  std::vector<Vec3> nodes_m;
  std::vector<std::array<int, 4>> tets;  // positively oriented: (x1-x0).((x2-x0)x(x3-x0)) > 0
};

// A boundary triangle, counter-clockwise seen from outside, and the tetrahedron it bounds.
struct BoundaryFace {
  std::array<int, 3> nodes;
  int tet = 0;
};

// The faces that belong to one tetrahedron only, in a deterministic order (by tetrahedron, then
// local face).
std::vector<BoundaryFace> boundary_faces(const TetMesh& mesh);

// Signed volume of tetrahedron t (> 0 for the positive orientation).
double tet_volume_m3(const TetMesh& mesh, int t);

// TetGen's quality fill ("pq1.5/12a<v>Q", as kernels/fem/solid_mesh.cpp) of a closed, outward,
// manifold triangle surface with linear tetrahedra of about edge_length_m, positively oriented.
// std::invalid_argument naming the reason for a surface TetGen cannot fill.
TetMesh tetrahedralize(const std::vector<Vec3>& vertices_m, const std::vector<std::array<int, 3>>& triangles,
                       double edge_length_m);

}  // namespace clatter::kernels::fracture
