// The three sources of a piece's base frequency omega_0 for equi-frequency scaling (003 section
// 5.4; docs/synth.md "Modal sound"), compared on a few meshes of glass:
// - "given": what a simulator that knows the piece would put in the scene; here a fine FEM of the
//   mesh (edge V^(1/3)/5), and Lamb's T2 for the sphere;
// - "mesh": clatter-synth's own FEM of the mesh at the default edge (V^(1/3)/2);
// - "proxy": the piece's equivalent ellipsoid (inertia and volume, eq. 11) in the same material,
//   i.e. a bank entry exactly at its shape, scaled to its size (a 320-triangle ellipsoid, FEM,
//   corrected for the volume the polyhedron misses).
// The table is printed for docs/synth.md; the mesh FEM must agree with the fine one to 2 % (the L
// prism's re-entrant edge converges slowest), and for
// the sphere all three with Lamb to 1 %.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "kernels/fem/lowest_mode.hpp"
#include "kernels/mass_properties.hpp"
#include "kernels/rigid_body.hpp"
#include "tests/reference/lamb_sphere.hpp"
#include "tests/reference/surfaces.hpp"

using namespace clatter;
using reference::Surface;

namespace {

constexpr double kE_pa = 6.2e10, kNu = 0.2, kRho = 2600;

double lowest_hz(const Surface& s, double edge_m = 0) {
  kernels::fem::LowestModeSettings settings;
  settings.edge_length_m = edge_m;
  return kernels::fem::lowest_free_mode(s.vertices_m, s.triangles, kE_pa, kNu, kRho, settings).frequency_hz;
}

// The equivalent ellipsoid's lowest frequency (the ideal proxy scaled to the piece).
double proxy_hz(const Surface& s) {
  const auto props = kernels::mesh_mass_properties(s.vertices_m, s.triangles);
  kernels::Mat3 inertia{};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) inertia[i][j] = kRho * props.inertia_per_density_m5[i][j];
  const auto fit = kernels::fit_proxy(inertia, kRho * props.volume_m3, props.volume_m3);
  const Surface e = reference::ellipsoid_surface({fit.a_m, fit.b_m, fit.c_m}, 2);
  // The inscribed polyhedron is smaller than the ellipsoid; frequency goes as 1 / size.
  const double polyhedron_m3 = kernels::mesh_mass_properties(e.vertices_m, e.triangles).volume_m3;
  return lowest_hz(e) * std::cbrt(polyhedron_m3 / (4.0 / 3.0 * std::numbers::pi * fit.a_m * fit.b_m * fit.c_m));
}

struct Row {
  const char* name;
  Surface surface;
  double given_hz = 0;  // 0: the fine FEM
};

}  // namespace

TEST(BaseFrequency, MeshFemAndProxyAgainstTheGivenValue) {
  const double pi = std::numbers::pi;
  const Surface sphere = reference::icosphere(0.1, 3);
  const auto t2 = reference::lamb_sphere_modes(kNu, 4.0).front();
  const double sphere_volume = kernels::mesh_mass_properties(sphere.vertices_m, sphere.triangles).volume_m3;
  const double a_eq = std::cbrt(3 * sphere_volume / (4 * pi));
  std::vector<Row> rows{{"sphere r 10 cm (1280 triangles)", sphere, reference::lamb_frequency_hz(t2, a_eq, kE_pa, kNu, kRho)},
                        {"box 20 x 10 x 5 cm", reference::box(0.2, 0.1, 0.05, 2)},
                        {"plate 20 x 20 x 2 cm", reference::box(0.2, 0.2, 0.02, 4)},
                        {"L prism 20 x 20 x 5 cm (non-convex)", reference::l_prism(0.1, 0.05)}};
  std::printf("| piece | given [Hz] | mesh FEM [Hz] (time) | vs given | proxy [Hz] | vs given |\n|---|---|---|---|---|---|\n");
  for (auto& r : rows) {
    const double volume = kernels::mesh_mass_properties(r.surface.vertices_m, r.surface.triangles).volume_m3;
    if (!(r.given_hz > 0)) r.given_hz = lowest_hz(r.surface, std::cbrt(volume) / 5);
    const auto t0 = std::chrono::steady_clock::now();
    const double mesh = lowest_hz(r.surface);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double proxy = proxy_hz(r.surface);
    std::printf("| %s | %.1f | %.1f (%.2f s) | %+.2f %% | %.1f | %+.1f %% |\n", r.name, r.given_hz, mesh, seconds,
                100 * (mesh / r.given_hz - 1), proxy, 100 * (proxy / r.given_hz - 1));
    EXPECT_NEAR(mesh / r.given_hz, 1.0, 0.02) << r.name;
  }
  EXPECT_NEAR(proxy_hz(sphere) / rows[0].given_hz, 1.0, 0.01);
}
