#include "kernels/transfer/mesh_locator.hpp"

#include <limits>

namespace clatter::kernels::transfer {

std::array<double, 3> nearest_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c, double* distance2_m2) {
  auto done = [&](std::array<double, 3> l) {
    if (distance2_m2) *distance2_m2 = (p - (l[0] * a + l[1] * b + l[2] * c)).squaredNorm();
    return l;
  };
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return done({1, 0, 0});
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return done({0, 1, 0});
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return done({1 - v, v, 0});
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return done({0, 0, 1});
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return done({1 - w, 0, w});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return done({0, 1 - w, w});
  }
  const double denom = 1 / (va + vb + vc), v = vb * denom, w = vc * denom;
  return done({1 - v - w, v, w});
}

MeshLocator::MeshLocator(std::span<const std::array<double, 3>> nodes_m, std::span<const std::array<std::int32_t, 6>> faces)
    : faces_(faces.begin(), faces.end()) {
  nodes_.reserve(nodes_m.size());
  for (const auto& x : nodes_m) nodes_.emplace_back(x[0], x[1], x[2]);
}

SurfacePoint MeshLocator::locate(const Eigen::Vector3d& x) const {
  double best = std::numeric_limits<double>::infinity();
  SurfacePoint out;
  for (const auto& f : faces_) {
    double d2 = 0;
    const auto l = nearest_barycentric(x, nodes_[static_cast<std::size_t>(f[0])], nodes_[static_cast<std::size_t>(f[1])],
                                       nodes_[static_cast<std::size_t>(f[2])], &d2);
    if (!(d2 < best)) continue;
    best = d2;
    out.nodes = f;
    // The 6-node triangle's shape functions: corners l_i (2 l_i - 1), mid-nodes of 01, 12, 20: 4 l_i l_j.
    out.weights = {l[0] * (2 * l[0] - 1), l[1] * (2 * l[1] - 1), l[2] * (2 * l[2] - 1),
                   4 * l[0] * l[1],       4 * l[1] * l[2],       4 * l[2] * l[0]};
  }
  return out;
}

}  // namespace clatter::kernels::transfer
