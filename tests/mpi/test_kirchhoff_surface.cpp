// The Kirchhoff surface of a solve (kernels/fdtd/kirchhoff.hpp) on real FDTD fields: against the grid's
// own listeners (the same solve, heard two ways) and against the exact translating sphere, near,
// at 3 m and in the far field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "banks/pan/solve_job.hpp"
#include "mpi/comm.hpp"
#include "tests/reference/sphere_exact.hpp"

using namespace clatter;

namespace {

std::string exact_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// Relative L2 of a surface series against want(t) on its valid samples.
template <class Want>
double rel_l2(const kernels::fdtd::KirchhoffSeries& s, double dt_s, Want want) {
  double num = 0, den = 0;
  for (int k = 0; k < s.valid_end; ++k) {
    const double w = want(s.t_first_s + k * dt_s), g = s.value[static_cast<std::size_t>(k)];
    num += (g - w) * (g - w);
    den += w * w;
  }
  return std::sqrt(num / den);
}

}  // namespace

TEST(FdtdKirchhoffSurface, TranslatingSphereHeardThroughTheSurfaceNearAtThreeMetresAndFar) {
  // A sphere of 0.1 m at 20 cells per radius translating along z (the FdtdSphere tests' fine grid),
  // octant mode; the Kirchhoff surface 3 cells off the sphere.
  io::Config c(jobs::solve_schema());
  const double a = 0.1, dx = a / 20;
  for (const char* k : {"object.a_m=0.1", "object.b_m=0.1", "object.c_m=0.1"}) c.set(k);
  c.set("grid.dx_m=" + exact_text(dx));
  c.set("grid.half_width_m=" + exact_text(0.33 + 8 * dx));
  c.set("time.dt_s=" + exact_text(0.5 * dx / 343.2));
  c.set("time.duration_s=0.0022");
  c.set("solve.fields=[3]");
  const double s37 = std::sin(37.0 * M_PI / 180), c37 = std::cos(37.0 * M_PI / 180);
  c.set("listeners.points_m=[[0, 0, 0.3], [" + exact_text(0.3 * s37) + ", 0, " + exact_text(0.3 * c37) + "]]");
  auto spec = jobs::make_solve_spec(c);
  spec.kirchhoff.radius_m = 0.115;
  spec.far_directions = {{0, 0, 1}, {s37, 0, c37}};
  spec.surface_listeners_m = {{0, 0, 0.3}, {0.3 * s37, 0, 0.3 * c37}, {0, 0, 3.0}, {3 * s37, 0, 3 * c37}};
  // The record must reach the pulse's passage at 3 m.
  spec.n_samples += static_cast<int>(std::ceil(2.7 / 343.2 / spec.problem.dt_s));
  const auto result = jobs::run_solve(MPI_COMM_WORLD, spec, 0.0);
  if (mpi::rank(MPI_COMM_WORLD) != 0) return;
  const auto& p = spec.problem;
  const reference::TranslatingSphere sphere{a, p.c_m_s, p.rho_kg_m3, p.h_s};
  const std::size_t ns = static_cast<std::size_t>(spec.n_samples);
  const double t_first = -spec.i_time_zero * p.dt_s;
  for (std::size_t l = 0; l < 2; ++l) {
    const double cos_theta = l == 0 ? 1.0 : c37;
    // The same solve heard at a grid listener and through the surface.
    const double grid_vs_surface = rel_l2(result.surface_series[0][l], p.dt_s, [&](double t) {
      const double k = (t - t_first) / p.dt_s;
      const auto i = static_cast<std::size_t>(std::lround(k));
      return i < ns ? static_cast<double>(result.series[0][l * ns + i]) : 0.0;
    });
    const double at_3m = rel_l2(result.surface_series[0][2 + l], p.dt_s, [&](double t) { return sphere.pressure(3.0, cos_theta, t); });
    // The exact far field: R p(R, tau + R/c) at R = 1e4 m, where the 1/R^2 term is 1e-6 of it.
    const double far_r = 1e4;
    const double far = rel_l2(result.far[0][l], p.dt_s, [&](double tau) {
      return far_r * sphere.pressure(far_r, cos_theta, tau + far_r / p.c_m_s);
    });
    std::printf("sphere, %s: surface vs grid listener at 0.3 m %.3f %%, surface at 3 m vs exact %.3f %%, far field vs exact %.3f %%\n",
                l == 0 ? "on the axis" : "37 degrees off", 100 * grid_vs_surface, 100 * at_3m, 100 * far);
    EXPECT_LT(grid_vs_surface, 0.01);
    EXPECT_LT(at_3m, 0.02);
    EXPECT_LT(far, 0.02);
  }
}

TEST(FdtdKirchhoffSurface, ElongatedProxyHeardThroughTheSurfaceAgreesWithTheGrid) {
  // The (0.5, 0.2625, 0.12) proxy at the demo bank's resolution (4 cm cells, h = 0.5 ms), a
  // translation and a rotation, at held-out points of docs/pan.md.
  io::Config c(jobs::solve_schema());
  for (const char* k : {"object.a_m=0.5", "object.b_m=0.2625", "object.c_m=0.12", "grid.dx_m=0.04", "pulse.h_s=0.0005",
                        "time.dt_s=4.1666666666666665e-05", "grid.half_width_m=1.9", "time.duration_s=0.018",
                        "solve.fields=[1, 4]"})
    c.set(k);
  const std::array<std::array<double, 3>, 2> d{{{0.37, 0.52, 0.77}, {0.8, 0.25, 0.55}}};
  std::vector<std::array<double, 3>> points;
  for (double r : {1.05, 1.35})
    for (const auto& u : d) {
      const double n = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      points.push_back({r * u[0] / n, r * u[1] / n, r * u[2] / n});
    }
  std::string text = "listeners.points_m=[";
  for (const auto& x : points) text += "[" + exact_text(x[0]) + ", " + exact_text(x[1]) + ", " + exact_text(x[2]) + "], ";
  c.set(text.substr(0, text.size() - 2) + "]");
  auto spec = jobs::make_solve_spec(c);
  spec.kirchhoff.radius_m = 0.62;
  spec.surface_listeners_m = points;
  const auto result = jobs::run_solve(MPI_COMM_WORLD, spec, 0.0);
  if (mpi::rank(MPI_COMM_WORLD) != 0) return;
  const std::size_t ns = static_cast<std::size_t>(spec.n_samples);
  const double t_first = -spec.i_time_zero * spec.problem.dt_s;
  for (std::size_t f = 0; f < 2; ++f)
    for (std::size_t l = 0; l < points.size(); ++l) {
      const double e = rel_l2(result.surface_series[f][l], spec.problem.dt_s, [&](double t) {
        const auto i = static_cast<std::size_t>(std::lround((t - t_first) / spec.problem.dt_s));
        return i < ns ? static_cast<double>(result.series[f][l * ns + i]) : 0.0;
      });
      std::printf("proxy (0.2625, 0.12), field %d, listener %zu: surface vs grid %.3f %%\n", spec.fields[f], l, 100 * e);
      EXPECT_LT(e, 0.01);
    }
}
