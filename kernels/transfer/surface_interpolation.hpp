#pragma once
// Values of a field given at the nodes of the bank's curved surface mesh (6-node triangles, the
// nodes on the ellipsoid) at arbitrary points of the exact ellipsoid. A point is located in the
// face whose corners, mapped to the unit sphere by (x/a, y/b, z/c), enclose its own image (a ray
// from the centre through a flat triangle); the face's quadratic shape functions at those
// barycentric coordinates interpolate. Locating is done once per point set.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace clatter::kernels::transfer {

// Half the mean corner-to-corner edge of the faces: the spacing of the mesh's nodes, mid-nodes
// included, at which a nodal field is known.
double surface_node_spacing_m(std::span<const std::array<double, 3>> nodes_m,
                              std::span<const std::array<std::int32_t, 6>> faces);

// Where a point of the ellipsoid lies on the mesh: a face's six nodes and their shape functions.
struct SurfacePoint {
  std::array<std::int32_t, 6> nodes{};
  std::array<double, 6> weights{};
  Eigen::Vector3d vector(std::span<const double> nodal) const;  // nodal: [node][3]
};

// The mesh's faces as seen from the centre, built once (the synthesizer locates a contact point
// per impact); the spans must outlive it.
class SurfaceLocator {
 public:
  SurfaceLocator(const std::array<double, 3>& axes_m, std::span<const std::array<double, 3>> nodes_m,
                 std::span<const std::array<std::int32_t, 6>> faces);
  ~SurfaceLocator();
  SurfaceLocator(SurfaceLocator&&) noexcept;
  SurfaceLocator& operator=(SurfaceLocator&&) noexcept;
  SurfacePoint locate(const Eigen::Vector3d& x_m) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class SurfaceInterpolator {
 public:
  SurfaceInterpolator(const std::array<double, 3>& axes_m, std::span<const std::array<double, 3>> nodes_m,
                      std::span<const std::array<std::int32_t, 6>> faces, std::span<const Eigen::Vector3d> points);

  // nodal: [node][3] vectors (a mode shape); the interpolated vector at each point.
  std::vector<Eigen::Vector3d> vectors(std::span<const double> nodal) const;

 private:
  std::vector<SurfacePoint> points_;
};

}  // namespace clatter::kernels::transfer
