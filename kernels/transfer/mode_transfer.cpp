#include "kernels/transfer/mode_transfer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernels/transfer/equivalent_sources.hpp"
#include "kernels/transfer/special_functions.hpp"
#include "kernels/transfer/surface_interpolation.hpp"

namespace clatter::kernels::transfer {
namespace {

int count(double length_m, double spacing_m, int minimum) {
  return std::max(minimum, static_cast<int>(std::ceil(length_m / spacing_m)));
}

struct Grids {
  SourceLayout layout;
  SurfacePoints fit, check;
};

Grids make_grids(const std::array<double, 3>& axes, double k, double data_spacing_m, double depth,
                 const TransferSettings& s) {
  const double lambda = 2 * std::numbers::pi / k;
  Grids g;
  const auto outer = octant_lengths_m(axes);
  auto [su, sv] = inner_layer_counts(axes, depth, std::min(lambda / s.sources_per_wavelength, 2 * data_spacing_m),
                                     s.minimum_per_angle);
  if (su * sv > s.max_sources_per_octant) {
    const double shrink = std::sqrt(static_cast<double>(s.max_sources_per_octant) / (su * sv));
    su = std::max(s.minimum_per_angle, static_cast<int>(su * shrink));
    sv = std::max(s.minimum_per_angle, static_cast<int>(sv * shrink));
  }
  g.layout.sources = inner_layer(axes, octant_grid(axes, su, sv), depth);
  // The sources' field holds orders up to about k rho (rho the layer's radius), whatever the
  // air wavelength on the surface: fit points `points_per_source` times the sources per angle
  // resolve it; and two per node spacing of the data, whose C0 kinks would alias otherwise.
  const int fu = std::max(count(outer[0], data_spacing_m / 2, s.minimum_per_angle),
                          static_cast<int>(std::ceil(s.points_per_source * su)));
  const int fv = std::max(count(outer[1], data_spacing_m / 2, s.minimum_per_angle),
                          static_cast<int>(std::ceil(s.points_per_source * sv)));
  g.fit = octant_grid(axes, fu, fv);
  g.check = octant_grid(axes, fu + 3, fv + 3);
  return g;
}

// g = scale u.n at the 8 mirror images of the points; `motion2` gets the weighted sum of |u|^2.
MirroredData neumann_data(const SurfacePoints& points, const SurfaceDisplacement& u, double scale, double* motion2) {
  MirroredData g;
  for (int s = 0; s < 8; ++s) {
    const auto values = u(points, s);
    auto& gs = g[static_cast<std::size_t>(s)];
    gs.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      gs[i] = scale * values[i].dot(mirror(points.normal[i], s));
      if (motion2) *motion2 += points.weight_m2[i] * values[i].squaredNorm();
    }
  }
  return g;
}

double boundary_residual(double k, const SourceFit& fit, const Grids& grids, const MirroredData& g_check) {
  const auto fields = class_fields(k, fit, grids.layout, grids.check);
  double err = 0, norm = 0;
  std::vector<std::complex<double>> p, dp;
  for (int s = 0; s < 8; ++s) {
    field_at_mirror(fields, s, p, dp);
    for (std::size_t i = 0; i < grids.check.size(); ++i) {
      const double w = grids.check.weight_m2[i], gi = g_check[static_cast<std::size_t>(s)][i];
      err += w * std::norm((fields.empty() ? std::complex<double>(0) : dp[i]) - gi);
      norm += w * gi * gi;
    }
  }
  return norm > 0 ? std::sqrt(err / norm) : 0.0;
}

Multipole expansion_of(double k, const SourceFit& fit, const SourceLayout& layout, double tail_tolerance) {
  double rho = 0;
  for (const auto& y : layout.sources.position_m) rho = std::max(rho, y.norm());
  const int order = source_order(k, rho);
  Multipole m;
  m.k_rad_m = k;
  m.order = order;
  m.coefficients.assign(static_cast<std::size_t>(harmonic_count(order)), 0.0);
  for (const auto& pf : fit.classes)
    for (std::size_t j = 0; j < layout.sources.size(); ++j)
      add_mirrored_monopole(k, order, layout.sources.position_m[j], pf.strengths(static_cast<Eigen::Index>(j)), pf.sigma,
                            m.coefficients);
  m.order = truncation_order(m.coefficients, order, tail_tolerance);
  m.coefficients.resize(static_cast<std::size_t>(harmonic_count(m.order)));
  return m;
}

}  // namespace

SurfaceDisplacement mesh_displacement(const std::array<double, 3>& axes_m, std::span<const std::array<double, 3>> nodes_m,
                                      std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shape) {
  return [=](const SurfacePoints& octant, int s) {
    std::vector<Eigen::Vector3d> x(octant.size());
    for (std::size_t i = 0; i < octant.size(); ++i) x[i] = mirror(octant.position_m[i], s);
    return SurfaceInterpolator(axes_m, nodes_m, faces, x).vectors(shape);
  };
}

ModeTransfer solve_mode_transfer(const std::array<double, 3>& axes_m, double omega_rad_s, double data_spacing_m,
                                 const SurfaceDisplacement& u, const TransferSettings& settings) {
  const double k = omega_rad_s / settings.sound_speed_m_s;
  const double scale = settings.air_density_kg_m3 * omega_rad_s * omega_rad_s;  // dp/dn = rho omega^2 u.n
  ModeTransfer best;
  best.boundary_residual = INFINITY;
  int attempt = 0;
  double previous = INFINITY;
  for (double depth : settings.source_depths) {
    ++attempt;
    const Grids grids = make_grids(axes_m, k, data_spacing_m, depth, settings);
    double motion2 = 0;
    const SourceFit fit = fit_sources(k, grids.fit, neumann_data(grids.fit, u, scale, &motion2), grids.layout,
                                      settings.class_threshold);
    const double residual = boundary_residual(k, fit, grids, neumann_data(grids.check, u, scale, nullptr));
    const double normal_fraction = motion2 > 0 ? fit.data_norm / (scale * std::sqrt(motion2)) : 0.0;
    if (residual < best.boundary_residual) {
      best.boundary_residual = residual;
      best.normal_fraction = normal_fraction;
      best.expansion = expansion_of(k, fit, grids.layout, settings.tail_tolerance);
      best.solution = std::make_shared<const ExteriorSolution>(ExteriorSolution{k, grids.layout, fit});
      best.amplification = 0;
      for (const auto& c : fit.classes) best.amplification = std::max(best.amplification, c.amplification);
      best.source_depth = depth;
      best.classes = static_cast<int>(fit.classes.size());
      best.sources = 8 * static_cast<int>(grids.layout.sources.size());
      best.fit_points = 8 * static_cast<int>(grids.fit.size());
    }
    best.attempts = attempt;
    // Judged against the surface motion: a mode whose g is mostly mesh noise is not refitted.
    if (best.boundary_residual * best.normal_fraction <= settings.residual_target) break;
    // A layer depth that did not halve the residual says the floor is the data's (C0 kinks of
    // u.n), not a resonance of the layer: further depths would not help either.
    if (attempt > 1 && residual > 0.5 * previous) break;
    previous = residual;
  }
  return best;
}

}  // namespace clatter::kernels::transfer
