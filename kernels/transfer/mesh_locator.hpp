#pragma once
// Where a point lies on a curved surface mesh of any shape (an object bank entry's 6-node
// triangles): the face whose flat corner triangle is nearest, and the quadratic shape functions at
// the nearest point's barycentric coordinates. The synthesizer's own-model voice takes a contact
// point there (the ellipsoid bank's SurfaceLocator casts a ray from the centre instead, which
// only a star-shaped surface allows).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "kernels/transfer/surface_interpolation.hpp"

namespace clatter::kernels::transfer {

class MeshLocator {
 public:
  // The spans are copied.
  MeshLocator(std::span<const std::array<double, 3>> nodes_m, std::span<const std::array<std::int32_t, 6>> faces);
  // Every face is tried (O(faces), no index): one call per impact on an object of a few thousand faces.
  SurfacePoint locate(const Eigen::Vector3d& x_m) const;

 private:
  std::vector<Eigen::Vector3d> nodes_;
  std::vector<std::array<std::int32_t, 6>> faces_;
};

// The barycentric coordinates (of a, b, c) of the point of triangle abc nearest p (Ericson,
// Real-Time Collision Detection, 5.1.5), and that point's squared distance from p.
std::array<double, 3> nearest_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c, double* distance2_m2 = nullptr);

}  // namespace clatter::kernels::transfer
