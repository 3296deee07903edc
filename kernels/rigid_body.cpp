#include "kernels/rigid_body.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace clatter::kernels {

ProxyFit fit_proxy(const Mat3& inertia, double mass, double volume) {
  if (!(mass > 0)) throw std::invalid_argument("mass must be > 0");
  if (!(volume > 0)) throw std::invalid_argument("volume must be > 0");
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      m(i, j) = inertia[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      if (!std::isfinite(m(i, j))) throw std::invalid_argument("inertia has a non-finite entry");
    }
  const double scale = m.cwiseAbs().maxCoeff();
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw std::invalid_argument("inertia is not symmetric");
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);  // ascending eigenvalues
  const Eigen::Vector3d moment = eig.eigenvalues();
  if (!(moment(0) > 0)) throw std::invalid_argument("inertia is not positive definite");
  if (moment(2) > (moment(0) + moment(1)) * (1 + 1e-9))
    throw std::invalid_argument("inertia violates the triangle inequality (largest moment > sum of the others)");
  const double f = 5.0 / (2.0 * mass);
  double a2 = f * (moment(1) + moment(2) - moment(0)), b2 = f * (moment(0) + moment(2) - moment(1)),
         c2 = f * (moment(0) + moment(1) - moment(2));
  c2 = std::max(c2, 1e-12 * a2);  // a flat piece: a thin ellipsoid, not a degenerate one
  const double abc = std::sqrt(a2 * b2 * c2), k = std::cbrt(volume / (4.0 / 3.0 * std::numbers::pi * abc));
  ProxyFit fit;
  fit.a_m = k * std::sqrt(a2);
  fit.b_m = k * std::sqrt(b2);
  fit.c_m = k * std::sqrt(c2);
  for (int i = 0; i < 3; ++i) fit.moments_kg_m2[static_cast<std::size_t>(i)] = moment(i);
  Eigen::Matrix3d axes = eig.eigenvectors();
  if (axes.determinant() < 0) axes.col(2) *= -1;  // right-handed, so cross products keep their sign
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) fit.axes[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = axes(i, j);
  return fit;
}

Vec3 to_proxy_frame(const ProxyFit& fit, const Vec3& v) {
  Vec3 out{};
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 3; ++i) out[j] += fit.axes[i][j] * v[i];
  return out;
}

}  // namespace clatter::kernels
