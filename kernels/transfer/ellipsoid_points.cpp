#include "kernels/transfer/ellipsoid_points.hpp"

#include <Eigen/Geometry>
#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

namespace clatter::kernels::transfer {
namespace {

struct GaussRule {
  std::vector<double> x, w;
};

GaussRule gauss_legendre(int n, double lo, double hi) {
  std::unique_ptr<gsl_integration_glfixed_table, decltype(&gsl_integration_glfixed_table_free)> table(
      gsl_integration_glfixed_table_alloc(static_cast<std::size_t>(n)), gsl_integration_glfixed_table_free);
  if (!table) throw std::runtime_error("Gauss-Legendre table: allocation failed");
  GaussRule rule;
  for (int i = 0; i < n; ++i) {
    double xi = 0, wi = 0;
    gsl_integration_glfixed_point(lo, hi, static_cast<std::size_t>(i), &xi, &wi, table.get());
    rule.x.push_back(xi);
    rule.w.push_back(wi);
  }
  return rule;
}

// Length of the quarter ellipse with semi-axes p, q (Ramanujan's second approximation / 4).
double quarter_perimeter(double p, double q) {
  const double h = std::pow((p - q) / (p + q), 2);
  return std::numbers::pi * (p + q) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h))) / 4;
}

}  // namespace

SurfacePoints octant_grid(const std::array<double, 3>& axes_m, int n_u, int n_v) {
  const auto [a, b, c] = axes_m;
  const GaussRule ru = gauss_legendre(n_u, 0, std::numbers::pi / 2), rv = gauss_legendre(n_v, 0, std::numbers::pi / 2);
  SurfacePoints points;
  for (int i = 0; i < n_u; ++i) {
    const double su = std::sin(ru.x[static_cast<std::size_t>(i)]), cu = std::cos(ru.x[static_cast<std::size_t>(i)]);
    for (int j = 0; j < n_v; ++j) {
      const double sv = std::sin(rv.x[static_cast<std::size_t>(j)]), cv = std::cos(rv.x[static_cast<std::size_t>(j)]);
      const Eigen::Vector3d x(a * su * cv, b * su * sv, c * cu);
      const Eigen::Vector3d xu(a * cu * cv, b * cu * sv, -c * su), xv(-a * su * sv, b * su * cv, 0);
      const Eigen::Vector3d cross = xu.cross(xv);  // outward: at (a, 0, 0) it is (bc, 0, 0)
      points.position_m.push_back(x);
      points.normal.push_back(cross.normalized());
      points.weight_m2.push_back(cross.norm() * ru.w[static_cast<std::size_t>(i)] * rv.w[static_cast<std::size_t>(j)]);
    }
  }
  return points;
}

SurfacePoints rim_grid(const std::array<double, 3>& axes_m, const std::vector<int>& per_row, bool midpoint) {
  const auto [a, b, c] = axes_m;
  const auto rule = [midpoint](int n) {
    if (!midpoint) return gauss_legendre(n, 0, std::numbers::pi / 2);
    GaussRule r;
    for (int i = 0; i < n; ++i) {
      r.x.push_back((i + 0.5) * std::numbers::pi / 2 / n);
      r.w.push_back(std::numbers::pi / 2 / n);
    }
    return r;
  };
  const GaussRule rt = rule(static_cast<int>(per_row.size()));
  SurfacePoints points;
  for (std::size_t i = 0; i < per_row.size(); ++i) {
    const double st = std::sin(rt.x[i]), ct = std::cos(rt.x[i]);
    const GaussRule rp = rule(per_row[i]);
    for (std::size_t j = 0; j < rp.x.size(); ++j) {
      const double sp = std::sin(rp.x[j]), cp = std::cos(rp.x[j]);
      const Eigen::Vector3d x(a * ct, b * st * cp, c * st * sp);
      const Eigen::Vector3d xt(-a * st, b * ct * cp, c * ct * sp), xp(0, -b * st * sp, c * st * cp);
      const Eigen::Vector3d cross = xt.cross(xp);  // outward: at (0, b, 0) it is (0, ac, 0)
      points.position_m.push_back(x);
      points.normal.push_back(cross.normalized());
      points.weight_m2.push_back(cross.norm() * rt.w[i] * rp.w[j]);
    }
  }
  return points;
}

std::array<double, 2> rim_lengths_m(const std::array<double, 3>& axes_m) {
  return {quarter_perimeter(axes_m[0], axes_m[2]), quarter_perimeter(axes_m[1], axes_m[2])};
}

std::array<double, 3> confocal_axes_m(const std::array<double, 3>& axes_m, double t) {
  const double shift = (1 - t * t) * axes_m[0] * axes_m[0];
  return {t * axes_m[0], std::sqrt(axes_m[1] * axes_m[1] - shift), std::sqrt(axes_m[2] * axes_m[2] - shift)};
}

std::array<double, 2> octant_lengths_m(const std::array<double, 3>& axes_m) {
  const auto [a, b, c] = axes_m;
  return {std::max(quarter_perimeter(a, c), quarter_perimeter(b, c)), quarter_perimeter(a, b)};
}

double min_curvature_radius_m(const std::array<double, 3>& axes_m, const Eigen::Vector3d& x) {
  const auto [a, b, c] = axes_m;
  const double h2 = x.x() * x.x() / std::pow(a, 4) + x.y() * x.y() / std::pow(b, 4) + x.z() * x.z() / std::pow(c, 4);
  const double abc2 = a * a * b * b * c * c;
  const double gauss = 1 / (abc2 * h2 * h2);
  const double mean = (a * a + b * b + c * c - x.squaredNorm()) / (2 * abc2 * h2 * std::sqrt(h2));
  return 1 / (mean + std::sqrt(std::max(0.0, mean * mean - gauss)));
}

double layer_depth_m(const std::array<double, 3>& axes_m, const Eigen::Vector3d& x, double depth) {
  const double a = axes_m[0];
  return depth * std::min(a, std::max(min_curvature_radius_m(axes_m, x), 0.5 * a));
}

namespace {

// (x/a)^2 + (y/b)^2 + (z/c)^2: below 1 inside.
double level(const std::array<double, 3>& axes_m, const Eigen::Vector3d& y) {
  return std::pow(y.x() / axes_m[0], 2) + std::pow(y.y() / axes_m[1], 2) + std::pow(y.z() / axes_m[2], 2);
}

// x moved inward by its layer depth d; where the inward normal crosses the thin body near a sharp
// rim and leaves through the other face within 1.5 d, d is shortened until it does not, so that
// every source keeps at least d / 2 of body beyond it.
Eigen::Vector3d source_below(const std::array<double, 3>& axes_m, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                             double depth) {
  double d = layer_depth_m(axes_m, x, depth);
  for (int i = 0; i < 20 && level(axes_m, x - 1.5 * d * n) >= 1; ++i) d *= 0.8;
  return x - d * n;
}

}  // namespace

SurfacePoints inner_layer(const std::array<double, 3>& axes_m, const SurfacePoints& surface, double depth) {
  SurfacePoints layer = surface;
  for (std::size_t i = 0; i < surface.size(); ++i)
    layer.position_m[i] = source_below(axes_m, surface.position_m[i], surface.normal[i], depth);
  return layer;
}

std::array<int, 2> inner_layer_counts(const std::array<double, 3>& axes_m, double depth, double spacing_cap_m,
                                      int minimum) {
  // Not a structured binding: the lambda below captures them (clang 14 cannot).
  const double a = axes_m[0], b = axes_m[1], c = axes_m[2];
  const int n = 96;
  const double step = std::numbers::pi / 2 / n;
  // Source position and local depth at parameters (u, v).
  const auto layer = [&](double u, double v, double* d) {
    const Eigen::Vector3d x(a * std::sin(u) * std::cos(v), b * std::sin(u) * std::sin(v), c * std::cos(u));
    const Eigen::Vector3d normal(x.x() / (a * a), x.y() / (b * b), x.z() / (c * c));
    *d = layer_depth_m(axes_m, x, depth);
    return Eigen::Vector3d(x - *d * normal.normalized());
  };
  double need_u = 0, need_v = 0;  // max over the octant of |dy/du| / spacing (and for v)
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = std::max(i * step, 1e-3), v = j * step;
      double d = 0, du = 0, dv = 0;
      const Eigen::Vector3d y = layer(u, v, &d);
      const Eigen::Vector3d yu = layer(u + 1e-4, v, &du), yv = layer(u, v + 1e-4, &dv);
      const double spacing = std::min(spacing_cap_m, d);
      need_u = std::max(need_u, (yu - y).norm() / 1e-4 / spacing);
      need_v = std::max(need_v, (yv - y).norm() / 1e-4 / spacing);
    }
  const auto count = [&](double need) { return std::max(minimum, static_cast<int>(std::ceil(need * std::numbers::pi / 2))); };
  return {count(need_u), count(need_v)};
}

}  // namespace clatter::kernels::transfer
