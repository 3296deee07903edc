// clatter-sim's physics against independent references: free fall (t = sqrt(2H/g), v =
// sqrt(2gH)), Newton's second law over a contact (momentum change = recorded impulse), statics (a
// resting body's contact impulse over T is m g T), the Voronoi pieces tiling their solid, and the
// event rule of sim/impacts.hpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "io/config.hpp"
#include "io/materials.hpp"
#include "kernels/mass_properties.hpp"
#include "tests/reference/surfaces.hpp"
#include "sim/impacts.hpp"
#include "sim/simulate.hpp"
#include "sim/voronoi.hpp"
#include "sim/world.hpp"

namespace clatter::sim {
namespace {

constexpr double kG = 9.81;

std::string write_obj(const reference::Surface& s, const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / ("clatter-sim-test-" + name + ".obj");
  std::ofstream out(path);
  out.precision(17);
  for (const auto& v : s.vertices_m) out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  for (const auto& t : s.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  return path.string();
}

// A config of one mesh body at `position`, everything else the defaults but no plate or pile.
io::Config one_body(const std::string& obj, const Vec3& position, const Vec3& velocity, double duration_s) {
  io::Config c(sim_schema());
  c.set("meshes.files=[\"" + obj + "\"]");
  c.set(fmt::format("meshes.positions_m=[[{},{},{}]]", position[0], position[1], position[2]));
  c.set(fmt::format("meshes.velocities_m_s=[[{},{},{}]]", velocity[0], velocity[1], velocity[2]));
  c.set(fmt::format("sim.duration_s={}", duration_s));
  c.set(fmt::format("sim.gravity_m_s2={}", kG));
  c.set("listeners.positions_m=[[3,3,3]]");
  c.set("bodies.base_frequency=false");  // the FEM is not what these tests check
  c.set("sim.bodies=[]");
  return c;
}

double min_z(const reference::Surface& s) {
  double z = INFINITY;
  for (const auto& v : s.vertices_m) z = std::min(z, v[2]);
  return z;
}

// Free fall from rest: the lowest point reaches the floor at t = sqrt(2H/g) with speed sqrt(2gH).
TEST(SimPhysics, DroppedSphereHitsAtFreeFallTimeAndSpeed) {
  const auto sphere = reference::icosphere(0.05, 3);
  const std::string obj = write_obj(sphere, "sphere");
  for (const double h_m : {0.25, 1.0}) {
    io::Config c = one_body(obj, {0, 0, h_m - min_z(sphere)}, {0, 0, 0}, std::sqrt(2 * h_m / kG) + 0.05);
    const double dt_s = c.real("sim.dt_s");
    const io::Scene scene = simulate(c, "");
    ASSERT_FALSE(scene.events.empty());
    const io::SceneEvent& first = scene.events.front();
    const double t_exact = std::sqrt(2 * h_m / kG), v_exact = std::sqrt(2 * kG * h_m);
    EXPECT_EQ(first.b, 0);
    EXPECT_FALSE(first.sustained) << "the landing is an impact";
    EXPECT_LE(std::abs(first.t_s - t_exact), dt_s) << "H " << h_m << ": first impact at " << first.t_s << " s, exact " << t_exact;
    EXPECT_LE(std::abs(first.normal_speed_m_s / v_exact - 1), 0.01) << "H " << h_m << ": " << first.normal_speed_m_s << " m/s, exact " << v_exact;
    std::printf("drop H %.2f m: first impact %.5f s (exact %.5f, step %.1e), normal speed %.4f m/s (exact %.4f, %.3f %%)\n", h_m,
                first.t_s, t_exact, dt_s, first.normal_speed_m_s, v_exact, 100 * (first.normal_speed_m_s / v_exact - 1));
  }
}

// Newton: m (v1 - v0) = (recorded impulses on the body) - m g T z over the run [0, T]. A box
// thrown spinning at the floor bounces, slides and rolls; every contact of the run counts.
TEST(SimPhysics, MomentumChangeEqualsRecordedImpulse) {
  const auto box = reference::box(0.08, 0.05, 0.03, 2);
  const std::string obj = write_obj(box, "box");
  for (const double gravity : {kG, 0.0}) {
    const Vec3 v0{1.5, 0.3, -2.0};
    io::Config c = one_body(obj, {0, 0, 0.1}, v0, 0.4);
    c.set(fmt::format("sim.gravity_m_s2={}", gravity));
    SimStats stats;
    const io::Scene scene = simulate(c, "", &stats);
    ASSERT_GE(scene.events.size(), 2u);
    const io::SceneObject& o = scene.objects.front();
    Vec3 j{};
    for (const auto& e : scene.events)
      for (int k = 0; k < 3; ++k) j[k] += e.a == o.id ? e.impulse_n_s[k] : -e.impulse_n_s[k];
    const double t_s = static_cast<double>(stats.steps) * c.real("sim.dt_s");
    const Vec3 v1 = stats.final_states.at(o.id).velocity_m_s;
    double err = 0, scale = 0;
    for (int k = 0; k < 3; ++k) {
      const double dp = o.mass_kg * (v1[k] - v0[k]) + (k == 2 ? o.mass_kg * gravity * t_s : 0);
      err = std::max(err, std::abs(dp - j[k]));
      scale = std::max(scale, std::abs(j[k]));
    }
    EXPECT_LE(err, 1e-9 * scale) << "g " << gravity;
    std::printf("momentum, g = %.2f: %zu events, recorded impulse (%.6f, %.6f, %.6f) N s, largest |dp - J| %.2e N s\n", gravity,
                scene.events.size(), j[0], j[1], j[2], err);
  }
}

// Statics: a box set down on the floor stays; its contacts carry its weight, m g T over T.
TEST(SimPhysics, RestingBodyImpulseIsItsWeight) {
  const auto box = reference::box(0.1, 0.08, 0.04, 2);
  const std::string obj = write_obj(box, "rest");
  io::Config c = one_body(obj, {0, 0, 0}, {0, 0, 0}, 1.0);
  SimStats stats;
  const io::Scene scene = simulate(c, "", &stats);
  const io::SceneObject& o = scene.objects.front();
  double jz = 0;
  std::size_t impacts = 0;
  for (const auto& e : scene.events) {
    jz += e.impulse_n_s[2], impacts += !e.sustained;
    if (!e.sustained) std::printf("impact at %g s: %g m/s, %g N s\n", e.t_s, e.normal_speed_m_s, e.impulse_n_s[2]);
  }
  const double t_s = static_cast<double>(stats.steps) * c.real("sim.dt_s");
  const double weight = o.mass_kg * kG * t_s;
  EXPECT_NEAR(jz / weight, 1.0, 0.01);
  EXPECT_EQ(impacts, 0u) << "a body set down makes no impact";
  const Vec3 v = stats.final_states.at(o.id).velocity_m_s;
  EXPECT_LT(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), 1e-3);
  std::printf("resting box %.4f kg over %.2f s: %zu events, impulse %.6f N s, m g T %.6f N s (%.4f %%)\n", o.mass_kg, t_s,
              scene.events.size(), jz, weight, 100 * (jz / weight - 1));
}

// The pieces tile the plate: volumes sum to the prism's (N/2) R^2 sin(2 pi/N) t, first moments to
// its centroid (0), and each piece is a closed outward mesh (positive volume).
TEST(SimVoronoi, PiecesTileTheSolid) {
  const double r = 0.12, t = 0.006;
  const int sides = 24;
  std::vector<HalfSpace> planes;
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * std::numbers::pi * (k + 0.5) / sides;
    planes.push_back({{std::cos(a), std::sin(a), 0}, r * std::cos(std::numbers::pi / sides)});
  }
  Uniform u(7);
  std::vector<Vec3> seeds;
  for (int i = 0; i < 40; ++i) seeds.push_back({(u() - 0.5) * 0.15, (u() - 0.5) * 0.15, (u() - 0.5) * t});
  const auto pieces = voronoi_pieces({-r, -r, -t / 2}, {r, r, t / 2}, planes, seeds);
  ASSERT_EQ(pieces.size(), seeds.size());
  double volume = 0;
  Vec3 moment{};
  for (const Piece& p : pieces) {
    const auto mp = kernels::mesh_mass_properties(p.vertices_m, p.triangles);
    EXPECT_GT(mp.volume_m3, 0);
    EXPECT_GT(p.fracture_area_m2, 0) << "every piece broke off a neighbour";
    volume += mp.volume_m3;
    for (int k = 0; k < 3; ++k) moment[k] += mp.volume_m3 * mp.centroid_m[k];
  }
  const double exact = 0.5 * sides * r * r * std::sin(2 * std::numbers::pi / sides) * t;
  EXPECT_NEAR(volume / exact, 1.0, 1e-12);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(moment[k] / (exact * r), 0.0, 1e-12);
}

// The rule of sim/impacts.hpp on a hand-made point: an impact of at most impact_window_s, then
// sustained events of sustain_window_s; a gap longer than quiet_s starts a new impact; every
// impulse is kept.
TEST(SimImpacts, EpisodesFollowTheDocumentedRule) {
  const double dt = 1e-3;
  ImpactRecorder::Rules rules;
  rules.impact_window_s = 3e-3, rules.sustain_window_s = 10e-3, rules.quiet_s = 2e-3, rules.min_speed_m_s = 0.01,
  rules.merge_distance_m = 0.01;
  ImpactRecorder r(dt, rules);
  auto sample = [](double speed, double j, double x) {
    ContactSample c;
    c.a = 1;
    c.point_m = {x, 0, 0};
    c.impulse_n_s = {0, 0, j};
    c.approach_speed_m_s = speed;
    return std::vector<ContactSample>{c};
  };
  double total = 0;
  for (int n = 0; n < 25; ++n) {  // lands at 1 m/s, then rests 24 steps
    r.add_step(n * dt, sample(n == 0 ? 1.0 : 0.0, n == 0 ? 0.5 : 0.01, 0.001 * (n % 2)));
    total += n == 0 ? 0.5 : 0.01;
  }
  r.add_step(25 * dt, {});
  r.add_step(26 * dt, {});
  r.add_step(27 * dt, {});  // quiet for 3 steps > quiet_s: the contact has ended
  r.add_step(28 * dt, sample(0.5, 0.2, 0.05));  // a new landing elsewhere
  total += 0.2;
  const auto events = r.finish();
  ASSERT_EQ(events.size(), 5u);  // impact [0, 3), sustained [3, 13), [13, 23), [23, 25), impact at 28
  EXPECT_FALSE(events[0].sustained);
  EXPECT_NEAR(events[0].impulse_n_s[2], 0.52, 1e-12);
  EXPECT_DOUBLE_EQ(events[0].normal_speed_m_s, 1.0);
  for (int i = 1; i <= 3; ++i) EXPECT_TRUE(events[i].sustained);
  EXPECT_NEAR(events[1].contact_time_s, 10e-3, 1e-15);
  EXPECT_NEAR(events[3].contact_time_s, 2e-3, 1e-15);
  EXPECT_FALSE(events[4].sustained);
  EXPECT_NEAR(events[4].t_s, 28 * dt, 1e-15);
  double sum = 0;
  for (const auto& e : events) sum += e.impulse_n_s[2];
  EXPECT_NEAR(sum, total, 1e-12);
}

// The scene a simulation writes reads back as the same values (shortest round-trip numbers),
// fracture events, sustained contacts, lifetimes and base frequencies included. The objects are
// mesh objects: their volume and inertia come from their OBJ (tests/sim/test_sim_meshes.cpp).
TEST(SimScene, WrittenSceneReadsBackExactly) {
  io::Config c(sim_schema());
  c.set("plate.pieces=8");
  c.set("sim.duration_s=0.45");
  c.set("bodies.base_frequency=false");
  const io::Scene scene = simulate(c, "");
  const auto path = (std::filesystem::temp_directory_path() / "clatter-sim-test-roundtrip.json").string();
  io::write_scene(scene, path, R"({"program": "test"})");
  const io::Scene back = io::read_scene(path);
  ASSERT_EQ(back.objects.size(), scene.objects.size());
  ASSERT_EQ(back.events.size(), scene.events.size());
  std::size_t fractures = 0, sustained = 0;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const auto &a = scene.objects[i], &b = back.objects[i];
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.mass_kg, b.mass_kg);
    EXPECT_TRUE(std::filesystem::is_regular_file(b.mesh_path)) << b.mesh_path;
    EXPECT_EQ(a.created_s, b.created_s);
    EXPECT_EQ(a.destroyed_s, b.destroyed_s);
    EXPECT_EQ(a.material, b.material);
  }
  for (std::size_t i = 0; i < scene.events.size(); ++i) {
    const auto &a = scene.events[i], &b = back.events[i];
    EXPECT_EQ(a.t_s, b.t_s);
    EXPECT_EQ(a.a, b.a);
    EXPECT_EQ(a.b, b.b);
    EXPECT_EQ(a.fracture, b.fracture);
    EXPECT_EQ(a.sustained, b.sustained);
    EXPECT_EQ(a.impulse_n_s, b.impulse_n_s);
    EXPECT_EQ(a.point_m, b.point_m);
    EXPECT_EQ(a.normal_speed_m_s, b.normal_speed_m_s);
    EXPECT_EQ(a.contact_time_s, b.contact_time_s);
    EXPECT_EQ(a.pose_a.position_m, b.pose_a.position_m);
    EXPECT_EQ(a.pose_a.orientation_wxyz, b.pose_a.orientation_wxyz);
    fractures += a.fracture, sustained += a.sustained;
  }
  EXPECT_EQ(fractures, 8u);
  EXPECT_GT(sustained, 0u);
  EXPECT_EQ(back.ground_material, scene.ground_material);
  EXPECT_EQ(back.listeners_m, scene.listeners_m);
  EXPECT_EQ(back.duration_s, scene.duration_s);
  EXPECT_EQ(back.materials.at(scene.ground_material).rho_kg_m3, scene.materials.at(scene.ground_material).rho_kg_m3);
}

}  // namespace
}  // namespace clatter::sim
