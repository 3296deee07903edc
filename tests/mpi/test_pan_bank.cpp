// The PAN bank against the raw FDTD signal it was fitted from and against the exact sphere
// solution (docs/validation.md). Banks go through the file (write, read) so quantization counts.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include "io/pan_bank.hpp"
#include "banks/pan/pan_job.hpp"
#include "kernels/pan/direction_mesh.hpp"
#include "kernels/pan/directions.hpp"
#include "kernels/contact.hpp"
#include "kernels/pan/field.hpp"
#include "kernels/pan/render.hpp"
#include "mpi/comm.hpp"
#include "tests/reference/compare.hpp"
#include "tests/reference/ellipsoid_added_mass.hpp"
#include "tests/reference/sphere_exact.hpp"
#include "tests/reference/test_meshes.hpp"
#include "io/mesh.hpp"

using namespace clatter;
using reference::HalfSine;
using reference::half_sine_acceleration;
using reference::relative_l2;

namespace {

bool root() { return mpi::rank(MPI_COMM_WORLD) == 0; }

model::PanProxy through_file(const jobs::PanSpec& spec, const model::PanProxy& proxy, const std::string& name) {
  model::PanBank bank;
  bank.header = jobs::pan_header(spec);
  bank.proxies.push_back(proxy);
  const std::string path = (std::filesystem::current_path() / name).string();
  io::write_pan_bank(path, bank, "test", "", 1);
  return io::read_pan_bank(path).proxies.at(0);
}


// The sphere proxy B = C = 0.5 at 3 cm cells, field 1 (translation along x), through a bank file;
// on non-root ranks the field is empty (the solve is collective, the checks run on rank 0).
struct SphereProxy {
  jobs::PanSpec spec;
  model::PanBankHeader bank;
  model::PanProxy proxy;
  kernels::pan::FieldView field() const { return {&bank, &proxy, 1}; }
};
// configs/pan-demo.toml's resolution (h = 5e-4 s, 4 cm, dt = 1/24000 s): the defaults are the
// paper's bank, far too slow for a test.
io::Config demo_config() {
  io::Config config(jobs::pan_schema());
  config.set("pulse.h_s=0.0005");
  config.set("grid.dx_m=0.04");
  config.set("time.dt_s=4.1666666666666665e-05");
  return config;
}

// One proxy's spec for one field of `config`, and the solve around that proxy.
struct OneField {
  jobs::PanSpec spec;
  jobs::SolveSpec solve;
};
OneField one_field(io::Config config, const std::string& b_c, double b_m, double c_m, int field) {
  config.set("proxies.list_m=[[" + b_c + "]]");
  config.set("solve.fields=[" + std::to_string(field) + "]");
  OneField out{jobs::make_pan_spec(config), {}};
  out.solve = out.spec.solve;
  out.solve.problem.body = {out.spec.a_m, b_m, c_m};
  return out;
}

// A direction uniform in the positive octant's cube, normalized: with probability one no vertex
// of any direction set.
std::array<double, 3> random_octant_direction(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::array<double, 3> d{u(rng), u(rng), u(rng)};
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (double& x : d) x /= n;
  return d;
}

SphereProxy sphere_proxy(const std::string& file) {
  io::Config config = demo_config();
  config.set("proxies.list_m=[[0.5, 0.5]]");
  config.set("grid.dx_m=0.03");
  config.set("solve.fields=[1]");
  SphereProxy out{jobs::make_pan_spec(config), {}, {}};
  out.bank = jobs::pan_header(out.spec);
  auto result = jobs::build_proxy(MPI_COMM_WORLD, out.spec, 0, {}, 0.0);
  if (root()) out.proxy = through_file(out.spec, result.proxy, file);
  return out;
}


// Relative L2 of the bank (through the file) against raw FDTD signals heard through the Kirchhoff
// surface at held-out radii (midway between consecutive stored radii, none stored) in a direction strictly inside a triangle, at
// epsilon = 0.01; proxy (0.35, 0.2) at the default (demo) resolution. Returns the largest error
// over the radii, per field.
constexpr std::array<double, 3> kInsideATriangle{0.37, 0.52, 0.77};
std::vector<double> errors_at(const jobs::PanSpec& spec, const std::vector<double>& radii, int divisions,
                              kernels::pan::Interpolation interpolation,
                              const std::array<double, 3>& direction = kInsideATriangle);

// `refined`: each field's directions refined (fit.direction_tolerance's default), or the layout of
// `divisions` alone.
std::vector<double> held_out_errors(int divisions, kernels::pan::Interpolation interpolation, bool refined) {
  io::Config config = demo_config();
  config.set("proxies.list_m=[[0.35, 0.2]]");
  config.set("fit.divisions=" + std::to_string(divisions));
  if (!refined) config.set("fit.direction_tolerance=0");
  const auto spec = jobs::make_pan_spec(config);
  std::vector<double> radii;
  for (std::size_t i = 0; i + 1 < spec.radii_m.size(); ++i) radii.push_back(0.5 * (spec.radii_m[i] + spec.radii_m[i + 1]));
  return errors_at(spec, radii, divisions, interpolation);
}

// The same check for any spec at any radii (rounded to whole steps) in any direction.
std::vector<double> errors_at(const jobs::PanSpec& spec, const std::vector<double>& wanted_radii, int divisions,
                              kernels::pan::Interpolation interpolation, const std::array<double, 3>& d) {
  const double step = spec.solve.problem.c_m_s * spec.solve.problem.dt_s;
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  std::vector<double> radii;
  std::vector<std::array<double, 3>> points;
  for (double r : wanted_radii) {
    // Whole steps, so the raw series lines up with PAN samples without interpolation.
    radii.push_back(std::round(r / step) * step);
    points.push_back({radii.back() * d[0] / n, radii.back() * d[1] / n, radii.back() * d[2] / n});
  }
  auto result = jobs::build_proxy(MPI_COMM_WORLD, spec, 0, points, 0.0);
  std::vector<double> worst(spec.solve.fields.size(), 0.0);
  if (!root()) return worst;
  const auto proxy = through_file(spec, result.proxy, "pan_heldout.h5");
  const auto header = jobs::pan_header(spec);
  const std::size_t ns = static_cast<std::size_t>(spec.solve.n_samples);
  for (std::size_t f = 0; f < spec.solve.fields.size(); ++f) {
    const int field = spec.solve.fields[f];
    std::printf("%2d divisions, %-9s field %d, relative L2 at r =", divisions,
                interpolation == kernels::pan::Interpolation::linear ? "linear," : "quadratic,", field);
    for (std::size_t l = 0; l < points.size(); ++l) {
      const double err =
          jobs::held_out_error(spec, header, proxy, field, points[l], result.extra_series[f].data() + l * ns, interpolation);
      worst[f] = std::max(worst[f], err);
      std::printf(" %.3f m: %.4f%s", radii[l], err, l + 1 < points.size() ? "," : "\n");
    }
  }
  return worst;
}

}  // namespace

TEST(PanBank, HeldOutRadiiAndDirectionWithin5PercentAtEpsilon001) {
  // The defaults: the paper's 45 directions refined per field where the far field asks for it,
  // interpolated quadratically, through a bank file (hierarchically coded): every field within 5 %.
  const auto errors = held_out_errors(8, kernels::pan::Interpolation::quadratic, true);
  for (std::size_t f = 0; f < errors.size(); ++f) EXPECT_LT(errors[f], 0.05) << "field " << f + 1;
}

TEST(PanBank, TheMergeChecksEachFieldAsTheBankStoresIt) {
  // The held-out check of each field at the merge (merge_pan_results; clatter-bank info prints it) reads it
  // as io::stored_field codes it in memory. The same points through a bank file, read back as the
  // synthesizer reads it, must give the same errors; the points are the same on every call and in
  // any list, differ between proxies, lie in the octant at the held-out radii, between the stored ones.
  io::Config config = demo_config();
  config.set("proxies.list_m=[[0.35, 0.2], [0.2, 0.1]]");
  config.set("solve.fields=[1, 5]");
  const auto spec = jobs::make_pan_spec(config);
  const auto points = jobs::held_out_points(spec, 0);
  ASSERT_EQ(points.size(), 8 * (spec.radii_m.size() - 1));
  EXPECT_EQ(points, jobs::held_out_points(spec, 0));
  EXPECT_NE(points, jobs::held_out_points(spec, 1));
  // Drawn from the proxy itself, not its place in the list: banks of other lists check it at the same points.
  io::Config swapped = demo_config();
  swapped.set("proxies.list_m=[[0.2, 0.1], [0.35, 0.2]]");
  swapped.set("solve.fields=[1, 5]");
  EXPECT_EQ(points, jobs::held_out_points(jobs::make_pan_spec(swapped), 1));
  for (std::size_t l = 0; l < points.size(); ++l) {
    const auto& x = points[l];
    const std::size_t i = l % spec.held_out_radii_m.size();
    EXPECT_NEAR(std::hypot(x[0], x[1], x[2]), spec.held_out_radii_m[i], 1e-12);
    EXPECT_GT(spec.held_out_radii_m[i], spec.radii_m[i]);
    EXPECT_LT(spec.held_out_radii_m[i], spec.radii_m[i + 1]);
    EXPECT_TRUE(x[0] > 0 && x[1] > 0 && x[2] > 0);
  }
  auto result = jobs::build_proxy(MPI_COMM_WORLD, spec, 0, points, 0.0);
  if (!root()) return;
  const auto header = jobs::pan_header(spec);
  const auto from_file = through_file(spec, result.proxy, "pan_held_out_check.h5");
  const std::size_t ns = static_cast<std::size_t>(spec.solve.n_samples);
  for (std::size_t f = 0; f < spec.solve.fields.size(); ++f) {
    const int field = spec.solve.fields[f];
    const auto check = jobs::check_held_out(spec, header, result.proxy, field, points, result.extra_series[f]);
    ASSERT_EQ(check.error.size(), points.size());
    double worst = 0;
    for (std::size_t l = 0; l < points.size(); ++l) {
      const double via_file =
          jobs::held_out_error(spec, header, from_file, field, points[l], result.extra_series[f].data() + l * ns);
      EXPECT_NEAR(check.error[l], via_file, 1e-9) << "field " << field << ", point " << l;
      worst = std::max(worst, check.error[l]);
    }
    std::printf("field %d: held-out worst %.2f %% over %zu points\n", field, 100 * worst, points.size());
  }
}

TEST(PanBank, LinearDirectionInterpolationOverUniformLayouts) {
  // Uniform layouts, no refinement, the paper's linear interpolation. Stored as the field itself
  // (format 4) the 45 directions held the translations within 5 % and the rotations, which vanish
  // on two mirror planes, needed 153; over their symmetry zeros (format 5) all six hold at 45
  // (2026-12-07: 1.9, 1.8, 1.9, 2.7, 2.8, 2.9 %). Guards for both layouts.
  const auto paper = held_out_errors(8, kernels::pan::Interpolation::linear, false);
  for (std::size_t f = 0; f < paper.size(); ++f) EXPECT_LT(paper[f], 0.05) << "field " << f + 1;
  const auto fine = held_out_errors(16, kernels::pan::Interpolation::linear, false);
  for (std::size_t f = 0; f < fine.size(); ++f) EXPECT_LT(fine[f], 0.05) << "field " << f + 1;
}

TEST(PanBank, AnElongatedProxyHoldsFromTheRadiiOutToEightMetresAtTheDemoResolution) {
  // Every listener, the held-out ones too, is heard through the Kirchhoff surface (within 0.1 % of
  // a grid that holds them at this resolution, docs/pan.md). The paper's two-term series fitted
  // over 0.7-1.5 m gave 12 % and 36 % at 3 m for fields 1 and 4 here, and the series with the far
  // field as q_1 and three terms 6.5 % and 7.6 % (docs/pan.md, "The radial model").
  io::Config config = demo_config();
  config.set("proxies.list_m=[[0.2625, 0.12]]");
  config.set("solve.fields=[1, 4]");
  const std::vector<double> radii{0.92, 1.35, 1.8, 2.5, 4.0, 8.0};
  // Along a stored direction, (2, 3, 3) / sqrt(22), only the radial model and the compression count.
  const auto spec = jobs::make_pan_spec(config);
  const auto along = errors_at(spec, radii, 8, kernels::pan::Interpolation::quadratic, {2.0, 3.0, 3.0});
  // Inside a triangle the direction grid adds its error, which grows outwards (where the far field
  // alone is left): 6 % and 9 % at 8 m with 45 directions, within 5 % with 153.
  config.set("fit.divisions=16");
  const auto fine = jobs::make_pan_spec(config);
  const auto inside = errors_at(fine, radii, 16, kernels::pan::Interpolation::quadratic);
  if (!root()) return;
  for (std::size_t f = 0; f < along.size(); ++f) {
    EXPECT_LT(along[f], 0.02) << "field " << spec.solve.fields[f];
    EXPECT_LT(inside[f], 0.05) << "field " << spec.solve.fields[f];
  }
}

TEST(PanBank, SphereProxyReproducesTheExactTranslatingSphere) {
  const SphereProxy sphere = sphere_proxy("pan_sphere.h5");
  if (!root()) return;
  const auto& p = sphere.spec.solve.problem;
  const reference::TranslatingSphere exact{0.5, p.c_m_s, p.rho_kg_m3, p.h_s};
  const auto& radii = sphere.spec.radii_m;
  for (double r : {0.5 * (radii[1] + radii[2]), 3 * radii.back()}) {
    const std::array<double, 3> x{0.6 * r, 0.48 * r, 0.64 * r};  // |x| = r, cos(theta_x) = 0.6
    const auto s = kernels::pan::evaluate(sphere.field(), x);
    // Field 1 translates along x: the dipole axis is x.
    const double err = relative_l2(s.p, [&](std::size_t k) { return exact.pressure(r, 0.6, s.t0_s + static_cast<double>(k) * s.dt_s); });
    std::printf("sphere proxy at r = %.3f m: relative L2 %.4f vs the exact solution\n", r, err);
    EXPECT_LT(err, 0.05) << "r = " << r;
  }
}

// Thin proxies against an exact reference: Lamb's added mass (tests/reference/ellipsoid_added_mass.hpp).
// As omega -> 0 the far field of a translation along an axis, heard along it, has the transfer
// R p = rho M (i omega) A / (4 pi c): its first moment int t R p dt = -rho M h / (4 pi c) for the
// acceleration psi(t; h) (int psi dt = h: psi is a partition of unity), whatever the origin of t
// (int R p dt = 0), and with no assumption of compactness (the pulse is shorter than the body).
// At 2 cm cells (2.5 cells through the thinnest proxy of the grid, C = 0.025 m). Measured: 1.0039,
// 1.0051, 0.9949 for field 3 of (0.5, 0.025), (0.2625, 0.025), (0.12, 0.025); 0.9988 and 0.9859 for
// fields 1 and 2 of the last; at the demo's 4 cm the last's field 3 is 1.029 (docs/validation.md).
TEST(PanBank, ThinProxiesTranslateWithLambsAddedMass) {
  io::Config config = demo_config();
  config.set("grid.dx_m=0.02");
  config.set("time.dt_s=2.0833333333333333e-05");
  struct Case {
    const char* b_c;
    double b_m, c_m;
    int field;
  };
  const Case cases[] = {{"0.5, 0.025", 0.5, 0.025, 3},
                        {"0.2625, 0.025", 0.2625, 0.025, 3},
                        {"0.12, 0.025", 0.12, 0.025, 1},
                        {"0.12, 0.025", 0.12, 0.025, 2},
                        {"0.12, 0.025", 0.12, 0.025, 3}};
  for (const Case& k : cases) {
    const OneField one = one_field(config, k.b_c, k.b_m, k.c_m, k.field);
    const auto& p = one.spec.solve.problem;
    double dipole_m3 = 0;
    auto hook = [&](std::size_t, const kernels::fdtd::SurfaceField& surface) {
      std::array<double, 3> axis{0.0, 0.0, 0.0};
      axis[static_cast<std::size_t>(k.field - 1)] = 1.0;
      const auto far = jobs::aligned_far_field(one.spec, 0, surface, axis);
      double moment = 0;
      for (std::size_t n = 0; n < far.size(); ++n) moment += static_cast<double>(n) * p.dt_s * far[n] * p.dt_s;
      dipole_m3 = -4.0 * std::numbers::pi * p.c_m_s / p.rho_kg_m3 * moment / p.h_s;
    };
    jobs::run_solve(MPI_COMM_WORLD, one.solve, 0.0, hook);
    if (!root()) continue;
    const double lamb = reference::ellipsoid_translation_dipole_m3(one.spec.a_m, k.b_m, k.c_m, k.field - 1);
    std::printf("proxy (%s), field %d: dipole %.5g m^3, Lamb's %.5g m^3, ratio %.4f\n", k.b_c, k.field, dipole_m3, lamb,
                dipole_m3 / lamb);
    EXPECT_NEAR(dipole_m3 / lamb, 1.0, 0.02) << k.b_c << " field " << k.field;
  }
}

// The pebble of the PanObjectBank tests: an icosphere of radius 7 cm, 5120 triangles, as an OBJ
// file named `name` (written by rank 0); and a pan-object config of it at the demo resolution with
// 3 cm cells, field 1.
namespace {
std::string write_pebble(const std::string& name) {
  const std::string path = (std::filesystem::current_path() / name).string();
  const auto mesh = reference::icosphere(0.07, 4);
  if (root()) std::ofstream(path) << io::obj_text(io::TriangleMesh{mesh.vertices, mesh.triangles});
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}
io::Config pebble_config(const std::string& mesh_path) {
  io::Config config(jobs::pan_object_schema());
  config.set("pulse.h_s=0.0005");
  config.set("grid.dx_m=0.03");
  config.set("time.dt_s=4.1666666666666665e-05");
  config.set("solve.fields=[1]");
  config.set("objects.meshes=[\"" + mesh_path + "\"]");
  return config;
}
// The pan-object entry of one mesh over the paper's layout alone (45 directions per octant, no
// refinement) and 4 radii (5 series per direction, not 9: half the hearing), through the bank file
// (on rank 0); `all_octants`: objects.all_octants.
std::pair<jobs::PanSpec, model::PanProxy> layout_entry(const std::string& mesh_path, const std::string& fields,
                                                       bool all_octants, const std::string& file) {
  io::Config config = pebble_config(mesh_path);
  config.set("solve.fields=" + fields);
  config.set("fit.divisions=8");
  config.set("fit.direction_tolerance=0");
  config.set("fit.radii_m=[0.7, 1.0, 1.5, 3.0]");
  config.set(std::string("objects.all_octants=") + (all_octants ? "true" : "false"));
  auto spec = jobs::make_pan_spec(jobs::parse_pan_object_params(config));
  auto built = jobs::build_proxy(MPI_COMM_WORLD, spec, 0, {}, 0.0);
  model::PanProxy entry;
  if (root()) entry = through_file(spec, built.proxy, file);
  return {std::move(spec), std::move(entry)};
}
}  // namespace

// A pan-object entry (000 section 5's per-object PAN) of a sphere given as a mesh: an icosphere of
// radius 7 cm (a pebble; 5120 triangles, vertices on the sphere, facets at most 0.2 mm (0.15 %)
// inside it), which the entry scales to A = 0.5 m. Through the bank file, against the sphere proxy
// B = C = 0.5 of the same resolution (the ellipsoid path) and against the exact translating sphere,
// at a radius between the stored ones (0.92 m) and at 3x the outermost (15 m). Measured: 0.32 % and
// 0.39 % to the proxy; 0.97 % and 1.26 % to the exact solution, the proxy's own 0.99 % and 1.26 %.
TEST(PanObjectBank, IcosphereEntryMatchesTheSphereProxyAndTheExactSphere) {
  const std::string mesh_path = write_pebble("pan_object_sphere.obj");
  const io::Config config = pebble_config(mesh_path);
  const auto spec = jobs::make_pan_spec(jobs::parse_pan_object_params(config));
  ASSERT_EQ(spec.bodies.size(), 1u);
  const auto built = jobs::build_proxy(MPI_COMM_WORLD, spec, 0, {}, 0.0);
  const SphereProxy sphere = sphere_proxy("pan_object_reference.h5");
  if (!root()) return;
  const model::PanProxy entry = through_file(spec, built.proxy, "pan_object_sphere.h5");
  // Keyed by the mesh as given; scaled about its centre of mass (the origin) to A.
  EXPECT_TRUE(entry.is_mesh());
  EXPECT_EQ(entry.mesh.key, io::mesh_hash(io::read_obj(mesh_path)));
  EXPECT_NEAR(entry.mesh.scale, 0.5 / 0.07, 1e-9);
  for (double x : entry.mesh.centre_of_mass_m) EXPECT_LT(std::abs(x), 1e-12);
  const model::PanBankHeader header = jobs::pan_header(spec);
  EXPECT_EQ(header.radii_m, sphere.bank.radii_m);
  const auto& p = spec.solve.problem;
  const reference::TranslatingSphere exact{0.5, p.c_m_s, p.rho_kg_m3, p.h_s};
  const auto& radii = spec.radii_m;
  for (double r : {0.5 * (radii[1] + radii[2]), 3 * radii.back()}) {
    const std::array<double, 3> x{0.6 * r, 0.48 * r, 0.64 * r};
    const auto mesh_series = kernels::pan::evaluate({&header, &entry, 1}, x);
    const auto proxy_series = kernels::pan::evaluate(sphere.field(), x);
    ASSERT_EQ(mesh_series.p.size(), proxy_series.p.size());
    // The support distance: A in every direction, less the facets (at most 2.3 degrees from a vertex: 0.4 mm).
    EXPECT_NEAR(mesh_series.t0_s, proxy_series.t0_s, 0.1 * p.dt_s);
    const double to_proxy = relative_l2(mesh_series.p, [&](std::size_t k) { return proxy_series.p[k]; });
    const double to_exact = relative_l2(mesh_series.p, [&](std::size_t k) {
      return exact.pressure(r, 0.6, mesh_series.t0_s + static_cast<double>(k) * mesh_series.dt_s);
    });
    const double proxy_to_exact = relative_l2(proxy_series.p, [&](std::size_t k) {
      return exact.pressure(r, 0.6, proxy_series.t0_s + static_cast<double>(k) * proxy_series.dt_s);
    });
    std::printf("icosphere entry at r = %.3f m: relative L2 %.4f to the sphere proxy's bank, %.4f to the exact "
                "solution (the proxy's: %.4f)\n", r, to_proxy, to_exact, proxy_to_exact);
    EXPECT_LT(to_proxy, 0.01) << "r = " << r;
    EXPECT_LT(to_exact, 0.02) << "r = " << r;
  }
}

// The eight-octant path of a mesh without mirror symmetry (full-domain solve, every octant its own
// directions, the field stored as it is, no parity), forced on the icosphere (objects.all_octants)
// so that the exact solution and the one-octant entry are references: at points in five octants,
// both entries against the exact translating sphere and against each other. The paper's layout
// alone (45 directions per octant, no refinement) and 4 radii keep the test short; both entries
// interpolate over the same directions, the one-octant entry the field over its symmetry zeros
// (for field 1 of a sphere, exactly its dipole's cos), the eight-octant one the field itself
// (with 15 directions per octant that costs 1.6-3.1 % against the exact solution, 0.9-1.0 % for the
// one-octant entry; with 45, 1.0-1.3 % against 1.0-1.1 %).
TEST(PanObjectBank, EightOctantEntryOfASymmetricMeshMatchesItsOneOctantEntryAndTheExactSphere) {
  const std::string mesh_path = write_pebble("pan_object_octants.obj");
  const auto [spec8, eight] = layout_entry(mesh_path, "[1]", true, "pan_object_octants8.h5");
  const auto [spec1, one] = layout_entry(mesh_path, "[1]", false, "pan_object_octants1.h5");
  if (!root()) return;
  EXPECT_FALSE(spec8.solve_full.problem.grid.octant);
  EXPECT_EQ(eight.octants(), 8);
  EXPECT_EQ(one.octants(), 1);
  for (int o = 1; o < 8; ++o) EXPECT_TRUE(eight.field(1, o).solved()) << "octant " << o;
  const model::PanBankHeader header = jobs::pan_header(spec8);
  const auto& p = spec8.solve.problem;
  const reference::TranslatingSphere exact{0.5, p.c_m_s, p.rho_kg_m3, p.h_s};
  const double r = 1.1;
  for (const std::array<double, 3> d : {std::array<double, 3>{0.6, 0.48, 0.64}, {-0.6, 0.48, 0.64}, {0.36, -0.48, -0.8},
                                        {-0.48, -0.36, 0.8}, {-0.64, -0.6, -0.48}}) {
    const std::array<double, 3> x{r * d[0], r * d[1], r * d[2]};
    const auto s8 = kernels::pan::evaluate({&header, &eight, 1}, x);
    const auto s1 = kernels::pan::evaluate({&header, &one, 1}, x);
    ASSERT_EQ(s8.p.size(), s1.p.size());
    auto to_exact = [&](const kernels::pan::Series& s) {
      return relative_l2(s.p, [&](std::size_t k) { return exact.pressure(r, d[0], s.t0_s + static_cast<double>(k) * s.dt_s); });
    };
    const double between = relative_l2(s8.p, [&](std::size_t k) { return s1.p[k]; });
    std::printf("icosphere, eight octants vs one, direction (%.2f, %.2f, %.2f) at %.1f m: %.4f apart; to the exact "
                "solution %.4f and %.4f\n", d[0], d[1], d[2], r, between, to_exact(s8), to_exact(s1));
    EXPECT_LT(between, 0.01);        // measured 0.40-0.62 %
    EXPECT_LT(to_exact(s8), 0.02);   // measured 1.00-1.26 % (the one-octant entry: 1.01-1.10 %)
  }
}

// An eight-octant entry whose mesh has one or two mirror planes (a plate, a mug across its handle):
// only the octants on one side of them are heard, the others are their images with the field's
// parity (PanBody::mirrored_axes). A square pyramid (mirror-symmetric in x and y, not in z: 2 of 8
// octants heard), fields 1 (odd in x) and 4 (odd in y), against the same entry with every octant
// heard (objects.all_octants): at points in six octants, four of them copies, the two must agree
// to the full-domain solve's own asymmetry, and the copies must carry the field's sign.
TEST(PanObjectBank, MirrorPlanesOfAMeshAreHeardOnceAndMatchEveryOctantHeard) {
  const std::string mesh_path = (std::filesystem::current_path() / "pan_object_pyramid.obj").string();
  const auto pyramid = reference::square_pyramid(0.05, 0.06);
  if (root()) std::ofstream(mesh_path) << io::obj_text(io::TriangleMesh{pyramid.vertices, pyramid.triangles});
  MPI_Barrier(MPI_COMM_WORLD);
  const auto [spec2, mirrored] = layout_entry(mesh_path, "[1, 4]", false, "pan_object_pyramid2.h5");
  const auto [spec8, heard] = layout_entry(mesh_path, "[1, 4]", true, "pan_object_pyramid8.h5");
  if (!root()) return;
  EXPECT_EQ(spec2.bodies[0].mirrored_axes, 3);
  EXPECT_EQ(spec2.bodies[0].heard_octants(), 2);
  EXPECT_EQ(spec8.bodies[0].heard_octants(), 8);
  EXPECT_EQ(mirrored.octants(), 8);
  const model::PanBankHeader header = jobs::pan_header(spec2);
  const double r = 1.1;
  for (const int field : {1, 4}) {
    double worst = 0;
    for (const std::array<double, 3> d : {std::array<double, 3>{0.6, 0.48, 0.64}, {-0.6, 0.48, 0.64}, {0.6, -0.48, 0.64},
                                          {-0.6, -0.48, 0.64}, {0.36, 0.48, -0.8}, {-0.36, -0.48, -0.8}}) {
      const std::array<double, 3> x{r * d[0], r * d[1], r * d[2]};
      const auto a = kernels::pan::evaluate({&header, &mirrored, field}, x);
      const auto b = kernels::pan::evaluate({&header, &heard, field}, x);
      ASSERT_EQ(a.p.size(), b.p.size());
      EXPECT_DOUBLE_EQ(a.t0_s, b.t0_s);
      const double apart = relative_l2(a.p, [&](std::size_t k) { return b.p[k]; });
      std::printf("pyramid, field %d, direction (%.2f, %.2f, %.2f) at %.1f m: mirrored copy vs heard %.2e apart\n", field,
                  d[0], d[1], d[2], r, apart);
      worst = std::max(worst, apart);
      // The image across x (field 1 odd there) or y (field 4): the same series, negated.
      const std::array<double, 3> image{field == 1 ? -x[0] : x[0], field == 4 ? -x[1] : x[1], x[2]};
      const auto c = kernels::pan::evaluate({&header, &mirrored, field}, image);
      EXPECT_LT(relative_l2(c.p, [&](std::size_t k) { return -a.p[k]; }), 1e-6) << "field " << field;
    }
    EXPECT_LT(worst, 1e-5) << "field " << field;  // measured up to 4.7e-8: the solve is symmetric to its rounding
  }
}

TEST(PanRender, HalfSineImpactOnASphereMatchesTheExactTranslatingSphere) {
  // A sphere of radius 0.1 m (the B = C = 0.5 proxy scaled by beta = 0.2) hit along x: a half-sine
  // acceleration of 1 ms, rendered at 44.1 kHz through eq. (15) and the bank, against the exact
  // translating sphere driven by the same acceleration, at 1 m (docs/validation.md).
  const SphereProxy sphere = sphere_proxy("pan_render_sphere.h5");
  if (!root()) return;
  const auto& p = sphere.spec.solve.problem;
  const double beta = 0.2, radius = 0.5 * beta, rate = 44100;
  kernels::pan::HalfSineAcceleration a;
  a.t0_s = 0.002;
  a.tau_s = 0.001;
  a.peak = {100.0, 0, 0, 0, 0, 0};  // m/s^2 along x
  const HalfSine hs{a.peak[0], a.t0_s, a.tau_s};
  for (const std::array<double, 3> x : {std::array<double, 3>{0.6, 0.48, 0.64}, {-0.8, 0.0, 0.6}}) {
    std::vector<double> out(static_cast<std::size_t>(0.012 * rate), 0.0);
    kernels::pan::render_impact(sphere.bank, sphere.proxy, beta, x, a, rate, 0.0, out);
    const double err = relative_l2(out, [&](std::size_t n) {
      return reference::translating_sphere_pressure(radius, p.c_m_s, p.rho_kg_m3, 1.0, x[0], static_cast<double>(n) / rate,
                                                    half_sine_acceleration, &hs, a.t0_s, a.t0_s + a.tau_s, 8);
    });
    std::printf("half-sine impact on a sphere, listener (%.2f, %.2f, %.2f) at 1 m: relative L2 %.4f vs exact\n", x[0], x[1],
                x[2], err);
    EXPECT_LT(err, 0.05);
  }
}

TEST(PanDirections, RefinementHoldsTheFarFieldBetweenItsDirectionsAtTheDemoResolution) {
  // Issue 32's adaptive direction sets (not yet in the bank): the (0.2625, 0.12) proxy's field 4
  // far field, refined at split points to 2 %, against itself at random directions (no vertex of
  // any layout). The paper's 45 directions miss many of them by over 5 % (so the check can fail).
  const OneField one = one_field(demo_config(), "0.2625, 0.12", 0.2625, 0.12, 4);
  const jobs::PanSpec& spec = one.spec;
  std::vector<double> adaptive, paper;
  std::size_t directions = 0;
  auto hook = [&](std::size_t, const kernels::fdtd::SurfaceField& surface) {
    const auto refined = jobs::refine_directions(spec, 0, surface, 0.02, 3, 5000);
    directions = refined.mesh.size();
    // The radiated rule (jobs::kRadiatedEnergy): against a yardstick with 100 times its energy
    // (1 %) the field is radiated and refines as against none; with 1000 times (0.1 %) it is not,
    // and stays at the layout: no split.
    const auto& own = refined.strength;
    EXPECT_GT(refined.splits, 0);
    EXPECT_EQ(jobs::refine_directions(spec, 0, surface, 0.02, 3, 5000, 100 * own.energy).splits,
              refined.splits);
    EXPECT_EQ(jobs::refine_directions(spec, 0, surface, 0.02, 3, 5000, 1000 * own.energy).splits, 0);
    const kernels::pan::DirectionMesh uniform(spec.divisions, 0);
    const double floor = jobs::far_field_floor(spec, 0, surface);
    std::mt19937 rng(5);
    for (int i = 0; i < 48; ++i) {
      const auto d = random_octant_direction(rng);
      const auto truth = jobs::aligned_far_field(spec, 0, surface, d);
      // The adaptive set as the bank interpolates it (over the symmetry zeros, then times them);
      // the paper's 45 directions as the paper does (the far field itself).
      for (const auto* mesh : {&refined.mesh, &uniform}) {
        const bool bank = mesh == &refined.mesh;
        std::vector<double> sum(truth.size()), vertex;
        kernels::pan::blend(mesh->locate(d), [&](std::size_t v) -> const std::vector<double>& {
          return vertex = bank ? jobs::stored_far_field(spec, 0, surface, mesh->direction(v))
                               : jobs::aligned_far_field(spec, 0, surface, mesh->direction(v));
        }, sum);
        if (bank)
          for (double& x : sum) x *= kernels::pan::symmetry_zeros(surface.field, d);
        (bank ? adaptive : paper).push_back(jobs::far_field_miss(sum, truth, floor));
      }
    }
  };
  jobs::run_solve(MPI_COMM_WORLD, one.solve, 0.0, hook);
  if (!root()) return;
  const double worst = *std::max_element(adaptive.begin(), adaptive.end());
  const double paper_worst = *std::max_element(paper.begin(), paper.end());
  std::printf("far field between directions, field 4: adaptive (%zu directions) worst %.2f %%, the paper's 45 worst %.2f %%\n",
              directions, 100 * worst, 100 * paper_worst);
  EXPECT_LT(worst, 0.05);
  EXPECT_GT(paper_worst, 0.05);
}

namespace {

// The cigar (B = C = 0.025) at 2 cm cells and a 0.2 ms pulse, one field refined to 4 %: its far
// field p at 64 random directions (no vertex) and, with `near_zero_plane`, 64 more within 0.5-5
// degrees of the plane y = 0 (where fields 2, 4 and 6 vanish), interpolated as the bank does. Each
// miss is the relative L2 of p against max(|p|, floor x the strongest |p| of the directions).
struct ListenerMisses {
  std::size_t directions = 0;
  double worst_tenth = 0;  // floor 0.1: the held-out check's "floored" column
  double worst_weak = 0;   // floor 0.015: down to 2e-4 of the strongest direction's energy
};
ListenerMisses cigar_listener_misses(int field, bool near_zero_plane) {
  io::Config config(jobs::pan_schema());
  config.set("pulse.h_s=0.0002");
  config.set("grid.dx_m=0.02");
  config.set("time.dt_s=2.0833333333333333e-05");
  const OneField one = one_field(config, "0.025, 0.025", 0.025, 0.025, field);
  const jobs::PanSpec& spec = one.spec;
  std::vector<double> misses, own;
  ListenerMisses out;
  auto hook = [&](std::size_t, const kernels::fdtd::SurfaceField& surface) {
    const auto refined = jobs::refine_directions(spec, 0, surface, 0.04, 3, 5000);
    out.directions = refined.mesh.size();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> sum(spec.length);
    for (int i = 0; i < (near_zero_plane ? 128 : 64); ++i) {
      std::array<double, 3> d = random_octant_direction(rng);
      if (i >= 64) {
        const double el = (0.5 + 4.5 * u(rng)) * std::numbers::pi / 180, az = u(rng) * std::numbers::pi / 2;
        d = {std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az)};
      }
      const auto truth = jobs::aligned_far_field(spec, 0, surface, d);
      kernels::pan::blend(refined.mesh.locate(d), [&](std::size_t v) {
        return jobs::stored_far_field(spec, 0, surface, refined.mesh.direction(v));
      }, sum);
      double num = 0, den = 0;
      for (std::size_t k = 0; k < sum.size(); ++k) {
        const double p = sum[k] * kernels::pan::symmetry_zeros(surface.field, d);
        num += (p - truth[k]) * (p - truth[k]);
        den += truth[k] * truth[k];
      }
      misses.push_back(std::sqrt(num));
      own.push_back(std::sqrt(den));
    }
  };
  jobs::run_solve(MPI_COMM_WORLD, one.solve, 0.0, hook);
  if (!root()) return out;
  const double strongest = *std::max_element(own.begin(), own.end());
  for (std::size_t i = 0; i < misses.size(); ++i) {
    out.worst_tenth = std::max(out.worst_tenth, misses[i] / std::max(own[i], 0.1 * strongest));
    out.worst_weak = std::max(out.worst_weak, misses[i] / std::max(own[i], 0.015 * strongest));
  }
  std::printf("cigar field %d, far field between %zu directions: worst miss in p against a tenth of the strongest %.2f %%, "
              "against 1.5 %% of it %.2f %%\n", field, out.directions, 100 * out.worst_tenth, 100 * out.worst_weak);
  return out;
}

}  // namespace

TEST(PanDirections, RefinementHoldsTheFarFieldWhereAListenerHearsIt) {
  // The refinement measures q = p / Z_f, the field over its symmetry zeros. A needle swinging about
  // y (the cigar, field 5) has q's peaks near the planes, where Z_f is small, and a strong p where
  // q is weak, 45 degrees off the axis. Measured against a tenth of q's peak alone, those
  // directions passed as converged while their far field missed by 10 % at the paper's resolution
  // (docs/pan.md, "The refinement's floor"). Here the far field misses by at most the tolerance and
  // an eighth (the split points are samples, not a bound). Measured: 1.89 % (1678 directions);
  // with the q floor alone 5.15 % (1340), with the floor at a tenth 3.13 % (1482).
  const ListenerMisses m = cigar_listener_misses(5, false);  // every rank solves; rank 0 measures
  if (!root()) return;
  EXPECT_LT(m.worst_tenth, 0.045);
}

TEST(PanDirections, RefinementHoldsTheFarFieldWhereItIsWeak) {
  // A listener is held to 5 % of its own field wherever the field is not negligible. The cigar's
  // swing about z (field 6) is zero on the plane y = 0 and weak beside it; with the refinement's
  // floor at a tenth of the strongest direction, directions 0.5-5 degrees off the plane missed by
  // up to 14 % of their own field and 5.90 % against 1.5 % of the strongest (1482 directions). At
  // the floor of 1.5 % (floor_from_strongest): 3.51 % (1678 directions).
  const ListenerMisses m = cigar_listener_misses(6, true);
  if (!root()) return;
  EXPECT_LT(m.worst_weak, 0.045);
  EXPECT_LT(m.worst_tenth, 0.045);
}
