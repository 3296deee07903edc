#include "tests/reference/kirchhoff_helmholtz.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace clatter::reference {

namespace kt = kernels::transfer;

double far_field_vs_kirchhoff_helmholtz(const kt::Multipole& expansion, const kt::ExteriorSolution& solution,
                                        const kt::SurfacePoints& grid, const std::function<std::vector<double>(int)>& g,
                                        double r_m) {
  const double k = solution.k_rad_m;
  // The surface samples over all 8 mirrors, once.
  std::vector<Eigen::Vector3d> y, n;
  std::vector<double> w, gs;
  std::vector<std::complex<double>> ps;
  const auto fields = kt::class_fields(k, solution.fit, solution.layout, grid);
  std::vector<std::complex<double>> p, dp;
  for (int m = 0; m < 8; ++m) {
    kt::field_at_mirror(fields, m, p, dp);
    const auto gm = g(m);
    for (std::size_t i = 0; i < grid.size(); ++i) {
      y.push_back(kt::mirror(grid.position_m[i], m));
      n.push_back(kt::mirror(grid.normal[i], m));
      w.push_back(grid.weight_m2[i]);
      gs.push_back(gm[i]);
      ps.push_back(p[i]);
    }
  }
  return far_field_vs_kirchhoff_helmholtz(expansion, y, n, w, ps, gs, r_m);
}

double far_field_vs_kirchhoff_helmholtz(const kt::Multipole& expansion, const std::vector<Eigen::Vector3d>& y,
                                        const std::vector<Eigen::Vector3d>& n, const std::vector<double>& w,
                                        const std::vector<std::complex<double>>& ps, const std::vector<double>& gs,
                                        double r_m) {
  constexpr double kPi = std::numbers::pi;
  const double k = expansion.k_rad_m;
  std::vector<Eigen::Vector3d> xs;
  std::vector<std::complex<double>> sums;
  for (int q = 0; q < 10; ++q) {
    const double z = 1 - (2 * q + 1) / 10.0, phi = q * kPi * (3 - std::sqrt(5.0));
    const Eigen::Vector3d x = r_m * Eigen::Vector3d(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    std::complex<double> sum = 0;
    for (std::size_t i = 0; i < y.size(); ++i) {
      const Eigen::Vector3d d = x - y[i];
      const double r = d.norm();
      const std::complex<double> green = std::polar(1 / (4 * kPi * r), -k * r);
      const std::complex<double> dgreen = (1.0 + std::complex<double>(0, k * r)) * green * d.dot(n[i]) / (r * r);
      sum += w[i] * (ps[i] * dgreen - green * gs[i]);
    }
    xs.push_back(x);
    sums.push_back(sum);
  }
  // A point on or near a mirror plane of a mode odd across it (the lattice's first point lies on
  // y = 0) has |p| = 0 or nearly (an FEM mode is odd only to its mesh's asymmetry), and the integral
  // there is mostly quadrature noise: the difference is taken relative to |p| where |p| is at least
  // 1 % of its largest over the lattice, and relative to that 1 % below it.
  double largest = 0, worst = 0;
  for (const auto& sum : sums) largest = std::max(largest, std::abs(sum));
  for (std::size_t q = 0; q < xs.size(); ++q)
    worst = std::max(worst, std::abs(std::abs(expansion.pressure(xs[q])) - std::abs(sums[q])) /
                                std::max(std::abs(sums[q]), 1e-2 * largest));
  return worst;
}

}  // namespace clatter::reference
