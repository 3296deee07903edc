// The general-shape exterior solve of kernels/transfer/mesh_transfer.hpp. The sphere, given as a
// curved 6-node mesh like any other body, against its exact field: normal displacement
// u.n = Re or Im Y_n^m on r = a radiates p = rho omega^2 Y h_n(kr) / (k h_n'(ka)) (the same part
// of Y). Bodies without a closed form (a capped cylinder, an L-shaped prism, a thin disk) against
// the Kirchhoff-Helmholtz integral of the solved surface pressure with the *prescribed* g, so
// that the fit's boundary error shows in the far field (tests/reference/kirchhoff_helmholtz.hpp).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include "kernels/transfer/mesh_transfer.hpp"
#include "kernels/transfer/special_functions.hpp"
#include "tests/reference/kirchhoff_helmholtz.hpp"
#include "tests/reference/surfaces.hpp"
#include "tests/unit/quadratic_meshes.hpp"

namespace {
using namespace clatter::kernels::transfer;
using clatter::test::QuadraticSurface;
constexpr double kPi = std::numbers::pi;

std::complex<double> harmonic(int n, int m, const Eigen::Vector3d& x) {
  std::vector<std::complex<double>> y(static_cast<std::size_t>(harmonic_count(n)));
  const Eigen::Vector3d d = x.normalized();
  spherical_harmonics(n, d.z(), std::atan2(d.y(), d.x()), y.data());
  return y[static_cast<std::size_t>(harmonic_index(n, m))];
}

std::vector<double> shape_of(const QuadraticSurface& s, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& u) {
  std::vector<double> shape;
  for (const auto& p : s.nodes_m) {
    const Eigen::Vector3d v = u({p[0], p[1], p[2]});
    shape.insert(shape.end(), {v.x(), v.y(), v.z()});
  }
  return shape;
}

constexpr double kRadius = 0.1;  // the sphere [m]

const QuadraticSurface& sphere() {
  // 1280 curved faces, every node on the sphere; corner edges ~0.13 a.
  static const QuadraticSurface s =
      clatter::test::quadratic_surface(clatter::test::icosphere(kRadius, 2), 1, clatter::test::onto_sphere(kRadius));
  return s;
}

struct SphereResult {
  double worst = 0;
  MeshTransfer t;
};

// The worst error of the complex p at r = 2a and 5a over 40 directions, relative to the largest
// |p| at that radius (so directions near the harmonic's nodal lines count in full).
SphereResult sphere_case(int n, int m, bool imaginary, double ka) {
  const auto& s = sphere();
  const TransferSettings settings;
  auto part = [&](std::complex<double> v) { return imaginary ? v.imag() : v.real(); };
  const auto shape = shape_of(s, [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(part(harmonic(n, m, x)) * x.normalized()); });
  const double k = ka / kRadius, omega = k * settings.sound_speed_m_s;
  SphereResult out;
  out.t = solve_mesh_mode_transfer(s.nodes_m, s.faces, shape, omega, settings);
  const auto dh = spherical_hankel2_derivative(spherical_hankel2(n, ka), ka);
  for (double r_over_a : {2.0, 5.0}) {
    const auto hr = spherical_hankel2(n, k * r_over_a * kRadius);
    const std::complex<double> radial =
        settings.air_density_kg_m3 * omega * omega * hr[static_cast<std::size_t>(n)] / (k * dh[static_cast<std::size_t>(n)]);
    double peak = 0, error = 0;
    for (int i = 0; i < 40; ++i) {
      const double ct = -0.95 + 1.9 * (i % 8) / 7.0, phi = 0.3 + 2 * kPi * (i / 8) / 5.0;
      const Eigen::Vector3d dir(std::sqrt(1 - ct * ct) * std::cos(phi), std::sqrt(1 - ct * ct) * std::sin(phi), ct);
      const std::complex<double> exact = radial * part(harmonic(n, m, dir));
      peak = std::max(peak, std::abs(exact));
      error = std::max(error, std::abs(out.t.expansion.pressure(r_over_a * kRadius * dir) - exact));
    }
    out.worst = std::max(out.worst, error / peak);
  }
  return out;
}

TEST(MeshTransferSphere, VibratingSphereWithinOnePercent) {
  struct Case {
    int n, m;
    bool imaginary;
  };
  for (const Case c : {Case{0, 0, false}, Case{1, 1, true}, Case{2, 0, false}, Case{3, 2, false}, Case{3, -3, true}})
    for (double ka : {0.5, 2.0, 5.0, 10.0, 20.0}) {
      const auto start = std::chrono::steady_clock::now();
      const SphereResult r = sphere_case(c.n, c.m, c.imaginary, ka);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      EXPECT_LT(r.worst, 0.01) << "n " << c.n << " m " << c.m << " ka " << ka;
      EXPECT_LT(r.t.boundary_residual, 0.01) << "n " << c.n << " m " << c.m << " ka " << ka;
      std::printf("sphere n %d m %2d %s ka %4.1f: p error %.2e, residual %.2e, %d sources (%d dipoles), %d cells, "
                  "depth %.2f a, order %d, attempts %d, %.2f s\n",
                  c.n, c.m, c.imaginary ? "Im" : "Re", ka, r.worst, r.t.boundary_residual, r.t.sources, r.t.dipoles,
                  r.t.fit_points, r.t.source_depth_m / kRadius, r.t.expansion.order, r.t.attempts, seconds);
    }
}

// The far field of the expansion at r = 20 x the body's radius against Kirchhoff-Helmholtz over
// a fine quadrature of the curved surface (3-point rule on parts `spacing` wide), with the
// solved surface pressure and the prescribed g = rho omega^2 u.n.
struct BodyResult {
  double far_field = 0;
  MeshTransfer t;
};
BodyResult body_case(const QuadraticSurface& s, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& u,
                     double k, double quadrature_spacing_m) {
  // The bank's truncation (10^-3 of the far field's L2 norm) would show at the weaker lobes of
  // a pattern, which the pointwise comparison counts in full; the fit is what is tested here.
  TransferSettings settings;
  settings.tail_tolerance = 1e-6;
  const auto shape = shape_of(s, u);
  const double omega = k * settings.sound_speed_m_s, scale = settings.air_density_kg_m3 * omega * omega;
  BodyResult out;
  out.t = solve_mesh_mode_transfer(s.nodes_m, s.faces, shape, omega, settings);
  const auto q = mesh_surface_points(s.nodes_m, s.faces, shape, quadrature_spacing_m);
  std::vector<std::complex<double>> p;
  std::vector<double> g;
  double radius = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    p.push_back(out.t.solution->field(q.position_m[i], q.normal[i]).pressure);
    g.push_back(scale * q.displacement_m[i].dot(q.normal[i]));
    radius = std::max(radius, q.position_m[i].norm());
  }
  out.far_field = clatter::reference::far_field_vs_kirchhoff_helmholtz(out.t.expansion, q.position_m, q.normal,
                                                                     q.weight_m2, p, g, 20 * radius);
  return out;
}

void report(const char* what, double k, const BodyResult& r) {
  std::printf("%s, k %.0f rad/m: far field vs Kirchhoff-Helmholtz %.2e, boundary residual %.2e, %d sources "
              "(%d dipoles), %d cells, depth %.1f mm, attempts %d\n",
              what, k, r.far_field, r.t.boundary_residual, r.t.sources, r.t.dipoles, r.t.fit_points,
              r.t.source_depth_m * 1e3, r.t.attempts);
}

// A smooth body with no symmetry: the sphere's directions x-hat pushed to
// r = a (1 + 0.25 z^2 + 0.15 x y + 0.1 x), a = 5 cm, given as a curved mesh like any other;
// rigid translation along an oblique axis (a dipole-like field whose monopole part must cancel)
// and a made-up smooth vibration.
TEST(MeshTransferBody, SmoothAsymmetricBodyFarFieldMatchesKirchhoffHelmholtz) {
  const double a = 0.05;
  auto radius = [](const std::array<double, 3>& p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    const double x = p[0] / n, y = p[1] / n, z = p[2] / n;
    return std::array<double, 3>{x, y, z} ;
  };
  const clatter::test::Projection onto = [&](const std::array<double, 3>& p, const std::array<double, 3>&,
                                             const std::array<double, 3>&) {
    const auto d = radius(p);
    const double r = a * (1 + 0.25 * d[2] * d[2] + 0.15 * d[0] * d[1] + 0.1 * d[0]);
    return std::array<double, 3>{r * d[0], r * d[1], r * d[2]};
  };
  auto m = clatter::test::icosphere(1.0, 2);
  for (auto& v : m.vertices_m) v = onto(v, v, v);
  const auto s = clatter::test::quadratic_surface(m, 1, onto);
  const auto translation = [](const Eigen::Vector3d&) -> Eigen::Vector3d { return {0.3e-6, -0.5e-6, 0.8e-6}; };
  const auto vibration = [a](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    return Eigen::Vector3d(0.5 * std::sin(3 * x.x() / a), std::cos(2 * x.y() / a), 0.7 * std::sin(2 * (x.x() + x.z()) / a)) * 1e-6;
  };
  // k a = 0.5 and 5 (a the mean radius); at k = 300 (k a = 15) the comparison is pointwise
  // relative and one of the 10 directions of the translation's pattern lies in a weak lobe
  // (|p| 1/27 of the peak): the 0.23 % boundary residual shows there as 3.2 % (0.12 % of the
  // peak; the expansion equals the sources' own field and their own Kirchhoff-Helmholtz
  // integral to 1e-5 there), so k = 300 is held to 5 %.
  for (double k : {10.0, 100.0, 300.0}) {
    const double bound = k < 200 ? 0.01 : 0.05;
    const double spacing = std::min(0.002, 2 * kPi / k / 20);  // the quadrature: 20 parts a wavelength
    const auto t = body_case(s, translation, k, spacing);
    report("smooth body, translation", k, t);
    EXPECT_LT(t.far_field, bound) << "k " << k;
    EXPECT_LT(t.t.boundary_residual, 0.01) << "k " << k;
    const auto v = body_case(s, vibration, k, spacing);
    report("smooth body, vibration", k, v);
    EXPECT_LT(v.far_field, bound) << "k " << k;
    EXPECT_LT(v.t.boundary_residual, 0.01) << "k " << k;
  }
}

// Sharp edges and thin bodies: measured, not yet within 1 % (docs/transfer.md "Any closed mesh",
// limits). A closed cylinder (radius 5 cm, 8 cm long) translating obliquely, and a thin disk
// (radius 5 cm, 4 mm thick) translating along its thin axis, whose odd field only the
// mid-surface dipoles make. The bounds are the measured state, so that a regression shows.
TEST(MeshTransferEdgesSlow, SharpRimsAndThinDiskAgainstKirchhoffHelmholtz) {
  auto m = clatter::test::cylinder(0.05, 0.08, 24, 3);
  for (auto& v : m.vertices_m) v[2] -= 0.04;
  const auto translation = [](const Eigen::Vector3d&) -> Eigen::Vector3d { return {0.3e-6, -0.5e-6, 0.8e-6}; };
  for (int refine : {1, 2}) {  // node spacing ~6 mm, ~3 mm
    const auto cylinder = clatter::test::quadratic_surface(m, refine, clatter::test::onto_cylinder(0.05));
    for (double k : {10.0, 60.0}) {
      const auto r = body_case(cylinder, translation, k, 0.002);
      std::printf("refine %d: ", refine);
      report("cylinder translation", k, r);
      EXPECT_LT(r.far_field, refine == 1 ? 0.2 : 0.05) << "k " << k;
    }
  }
  const auto disk = clatter::test::plate(0.05, 0.004, 10);
  for (double k : {10.0, 60.0}) {
    const auto r = body_case(disk, [](const Eigen::Vector3d&) -> Eigen::Vector3d { return {0.2e-6, 0, 1e-6}; }, k, 0.001);
    report("thin disk translation", k, r);
    EXPECT_LT(r.far_field, 0.5) << "k " << k;
    EXPECT_GT(r.t.dipoles, 0);
  }
}

// The cost of the 26 cm ceramic plate, 6 mm thick (mesh edges ~5 mm), at 2, 8 and 20 kHz, with
// a made-up bending mode at the Kirchhoff plate's wavenumber (E 70 GPa, rho 2400 kg/m^3,
// nu 0.22): measured for docs/transfer.md, not timed pass/fail.
TEST(MeshTransferEdgesSlow, PlateCost) {
  const auto s = clatter::test::plate(0.13, 0.006, 26);
  const double bending_stiffness = 70e9 * std::pow(0.006, 3) / (12 * (1 - 0.22 * 0.22)), mass_per_area = 2400 * 0.006;
  for (double f_hz : {2000.0, 8000.0, 20000.0}) {
    const double omega = 2 * kPi * f_hz;
    const double kb = std::pow(omega * omega * mass_per_area / bending_stiffness, 0.25);
    const auto shape = shape_of(s, [kb](const Eigen::Vector3d& x) -> Eigen::Vector3d {
      return {0, 0, 1e-3 * std::cos(kb * (0.8 * x.x() + 0.6 * x.y()) + 0.3) * std::cos(0.7 * kb * x.y())};
    });
    const auto start = std::chrono::steady_clock::now();
    const auto t = solve_mesh_mode_transfer(s.nodes_m, s.faces, shape, omega, TransferSettings{});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("plate %5.0f Hz (%zu faces): %.1f s, %d sources (%d dipoles), %d cells, %d check points, spacing %.1f mm, "
                "residual %.3e, amplification %.1e, order %d, attempts %d\n",
                f_hz, s.faces.size(), seconds, t.sources, t.dipoles, t.fit_points, t.check_points,
                t.source_spacing_m * 1e3, t.boundary_residual, t.amplification, t.expansion.order, t.attempts);
    EXPECT_TRUE(std::isfinite(t.boundary_residual));
  }
}

}  // namespace
