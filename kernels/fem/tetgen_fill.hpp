#pragma once
// The TetGen plumbing both meshers share (ellipsoid_mesh.cpp, solid_mesh.cpp): a triangle PLC into
// tetgenio, TetGen's tetrahedra out, and the orientation of a tetrahedron. Private to kernels/fem:
// tetgen.h is included here alone.
#include <array>
#include <string>
#include <vector>

namespace clatter::kernels::fem {

// Tetrahedra as vertex quadruples over `points` (TetGen's output; the input points come first).
struct LinearMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 4>> tets;
};

struct TetgenFill {
  LinearMesh mesh;
  int failure_code = 0;        // TetGen's exit code when it gave up (TETLIBRARY throws it), else 0
  int intersecting_faces = 0;  // with detect_intersections: faces TetGen found crossing another
  // The crossing faces (with detect_intersections), else the mesh's boundary faces as TetGen wrote
  // them, and with facet_markers the input triangle each lies in (TetGen may split the input's).
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_facet;
};

// TetGen on the facets `triangles` (indices into `points`; every point is kept) with `switches`.
// With detect_intersections, TetGen's own test ("pdQ") runs first and, if it finds crossing
// faces, the fill is not attempted (TetGen 1.5's fill aborts on them). An empty mesh with
// failure_code 0 means TetGen returned no tetrahedra; refused switches throw std::invalid_argument.
// Empty switches: the intersection test alone. `holes`: a point inside each cavity (TetGen fills
// every region the facets enclose unless told).
TetgenFill tetgen_fill(const std::vector<std::array<double, 3>>& points, const std::vector<std::array<int, 3>>& triangles,
                       const std::string& switches, bool detect_intersections = false, bool facet_markers = false,
                       const std::vector<std::array<double, 3>>& holes = {});

// 6 times the signed volume of tetrahedron t (> 0: TetGen's positive orientation).
double orientation(const LinearMesh& m, const std::array<int, 4>& t);

}  // namespace clatter::kernels::fem
