#include "kernels/rigid_body.hpp"

#include <gsl/gsl_mode.h>
#include <gsl/gsl_sf_ellint.h>

#include <Eigen/Dense>
#include <algorithm>
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

double ellipsoid_surface_area_m2(double a, double b, double c) {
  if (!(a > 0) || !(b > 0) || !(c > 0)) throw std::invalid_argument("ellipsoid_surface_area_m2: semi-axes must be > 0");
  std::array<double, 3> r{a, b, c};
  std::sort(r.begin(), r.end(), std::greater<>());
  const double pi = std::numbers::pi;
  // Within 1e-6 of a sphere the formula's 0/0 costs digits; the area there is 4 pi a^2 to 1e-6.
  if (r[2] > r[0] * (1 - 1e-6)) return 4 * pi * r[0] * r[1] * r[2] / std::cbrt(r[0] * r[1] * r[2]);
  const double phi = std::acos(r[2] / r[0]), sin_phi = std::sin(phi), cos_phi = r[2] / r[0];
  const double k = std::sqrt(std::clamp(r[0] * r[0] * (r[1] * r[1] - r[2] * r[2]) / (r[1] * r[1] * (r[0] * r[0] - r[2] * r[2])), 0.0, 1.0));
  const double e = gsl_sf_ellint_E(phi, k, GSL_PREC_DOUBLE), f = gsl_sf_ellint_F(phi, k, GSL_PREC_DOUBLE);
  return 2 * pi * r[2] * r[2] + 2 * pi * r[0] * r[1] / sin_phi * (e * sin_phi * sin_phi + f * cos_phi * cos_phi);
}

}  // namespace clatter::kernels
