#pragma once
// Values of a field given at the nodes of the bank's curved surface mesh (6-node triangles, the
// nodes on the ellipsoid) at arbitrary points of the exact ellipsoid. A point is located in the
// face whose corners, mapped to the unit sphere by (x/a, y/b, z/c), enclose its own image (a ray
// from the centre through a flat triangle); the face's quadratic shape functions at those
// barycentric coordinates interpolate. Locating is done once per point set.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace clatter::kernels::transfer {

// Half the mean corner-to-corner edge of the faces: the spacing of the mesh's nodes, mid-nodes
// included, at which a nodal field is known.
double surface_node_spacing_m(std::span<const std::array<double, 3>> nodes_m,
                              std::span<const std::array<std::int32_t, 6>> faces);

class SurfaceInterpolator {
 public:
  SurfaceInterpolator(const std::array<double, 3>& axes_m, std::span<const std::array<double, 3>> nodes_m,
                      std::span<const std::array<std::int32_t, 6>> faces, std::span<const Eigen::Vector3d> points);

  // nodal: [node][3] vectors (a mode shape); the interpolated vector at each point.
  std::vector<Eigen::Vector3d> vectors(std::span<const double> nodal) const;

 private:
  std::vector<std::array<std::int32_t, 6>> nodes_of_point_;
  std::vector<std::array<double, 6>> weights_;
};

}  // namespace clatter::kernels::transfer
