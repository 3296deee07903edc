// The synthesizer end to end against the exact translating sphere (docs/validation.md), on a
// bank that `clatter-bank pan` made. Serial: it links what clatter-synth links.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "io/pan_bank.hpp"
#include "kernels/mass_properties.hpp"
#include "io/scene.hpp"
#include "kernels/contact.hpp"
#include "synth/render_scene.hpp"
#include "synth/sources.hpp"
#include "tests/reference/compare.hpp"
#include "tests/reference/sphere_exact.hpp"
#include "tests/synth/bank_paths.hpp"
#include "tests/unit/make_material.hpp"

using namespace clatter;
using reference::HalfSine;
using reference::half_sine_acceleration;
using reference::relative_l2;

namespace {

const std::string& bank_path = test::pan_bank_path;

// A scene holding one solid rock sphere (id 1, rho 2600 kg/m^3, E 50 GPa) and no events yet.
io::Scene one_sphere_scene(const std::string& path, double radius_m) {
  const double pi = 3.14159265358979323846, volume = 4.0 / 3.0 * pi * radius_m * radius_m * radius_m, mass = 2600 * volume;
  const double moment = 0.4 * mass * radius_m * radius_m;
  io::Scene scene;
  scene.path = path;
  scene.materials["rock"] = clatter::test::elastic(5e10, 0.25);
  scene.ground_material = "rock";
  io::SceneObject sphere;
  sphere.id = 1;
  sphere.mass_kg = mass;
  sphere.volume_m3 = volume;
  sphere.inertia_kg_m2 = {{{moment, 0, 0}, {0, moment, 0}, {0, 0, moment}}};
  sphere.material = "rock";
  scene.objects.push_back(sphere);
  return scene;
}

}  // namespace

TEST(Synth, SingleImpulseOnASphereMatchesTheExactTranslatingSphere) {
  // The whole synthesizer path: a scene with one solid sphere (radius 0.1 m, rock-like) struck
  // through its centre, Hertz duration, half-sine force, proxy fit from the inertia (eq. 11),
  // nearest bank proxy (the sphere B = C = 0.5), beta = 0.2, the listener rotated into the body
  // frame; against the exact translating sphere with acceleration (F_max / m) S(t; t0, tau).
  // The bank (proxies (0.5, 0.5) and (0.35, 0.2), 3 cm cells, fields 1-3) is made by
  // `clatter-bank pan` (CTest fixture synth_sphere_bank): this program is serial, like clatter-synth.
  ASSERT_FALSE(bank_path.empty()) << "usage: clatter-synth-tests PAN.h5 [MODAL.h5]";
  synth::PanSource pan(bank_path);
  const model::PanBankHeader header = io::read_pan_bank(bank_path).header;

  const double radius = 0.1;
  io::Scene scene = one_sphere_scene("sphere-scene", radius);
  const double mass = scene.objects.front().mass_kg;
  io::SceneEvent e;
  e.t_s = 0.002;
  e.a = 1;
  e.b = 0;
  const double angle = 0.7;  // the body is turned about z: the synthesizer must undo it
  e.pose_a.position_m = {0.2, -0.1, 0.3};
  e.pose_a.orientation_wxyz = {std::cos(angle / 2), 0, 0, std::sin(angle / 2)};
  const std::array<double, 3> dir{0.6, 0.0, 0.8};  // unit, through the centre: no torque
  e.point_m = {0.2 - radius * dir[0], -0.1 - radius * dir[1], 0.3 - radius * dir[2]};
  const double j = 0.05;
  e.impulse_n_s = {j * dir[0], j * dir[1], j * dir[2]};
  e.normal_speed_m_s = 0.02;  // slow: a long contact, resolved by the demo-resolution bank
  e.where = "sphere-scene: events[0]";
  scene.events.push_back(e);
  const std::array<double, 3> listener{0.2 + 0.6, -0.1 + 0.48, 0.3 + 0.64};  // 1 m away
  scene.listeners_m.push_back(listener);
  scene.duration_s = 0.012;
  synth::RenderOptions options;
  const auto out = synth::render_scene(scene, {&pan}, options);
  // The reference: Hertz with m* = m, R* = radius, the same materials.
  const model::Material rock = clatter::test::elastic(5e10, 0.25);
  const double tau = kernels::hertz_contact_time_s(mass, radius, rock, rock, e.normal_speed_m_s);
  const HalfSine hs{kernels::half_sine_peak(j, tau) / mass, e.t_s, tau};
  const double cos_theta = 0.6 * dir[0] + 0.48 * dir[1] + 0.64 * dir[2];
  const double err = relative_l2(out[0][0], [&](std::size_t n) {
    return reference::translating_sphere_pressure(radius, header.c_m_s, header.rho_kg_m3, 1.0, cos_theta,
                                                  static_cast<double>(n) / options.rate_hz, half_sine_acceleration, &hs, e.t_s,
                                                  e.t_s + tau, 8);
  });
  std::printf("synth: sphere (r = 0.1 m, tau = %.3g ms) at 1 m: relative L2 %.4f vs the exact translating sphere\n",
              tau * 1e3, err);
  EXPECT_LT(err, 0.05);
}

TEST(Synth, AnObjectWithItsOwnPanMatchesTheExactTranslatingSphere) {
  // An object given by a mesh whose own PAN a pan-object bank holds (-P, no proxy bank): a pebble,
  // the icosphere of radius 0.1 m (5120 triangles, vertices on the sphere) that the fixture
  // synth_pebble_pan built the bank of (3 cm cells at the entry's scale, fields 1-3). Struck
  // through its centre with a given contact time, turned about z; against the exact translating
  // sphere of radius 0.1 m with acceleration (F_max / m) S(t; t0, tau), m from the mesh's volume.
  ASSERT_FALSE(test::object_pan_path.empty()) << "usage: clatter-synth-tests PAN.h5 MODAL.h5 OBJECT_PAN.h5 MESH.obj";
  synth::PanSource pan("", {test::object_pan_path});
  const model::PanBankHeader header = io::read_pan_bank(test::object_pan_path).header;
  const double radius = 0.1, density = 2600;
  io::Scene scene = one_sphere_scene("pebble-scene", radius);
  io::SceneObject& pebble = scene.objects.front();
  pebble.mesh_path = test::object_pan_mesh_path;
  pebble.mesh = std::make_shared<const io::TriangleMesh>(io::read_obj(pebble.mesh_path));
  const auto solid = kernels::mesh_mass_properties(pebble.mesh->vertices_m, pebble.mesh->triangles);
  pebble.volume_m3 = solid.volume_m3;
  pebble.mass_kg = density * solid.volume_m3;
  pebble.rest_centre_m = solid.centroid_m;
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) pebble.inertia_kg_m2[r][c] = density * solid.inertia_per_density_m5[r][c];
  io::SceneEvent e;
  e.t_s = 0.002;
  e.a = 1;
  e.b = 0;
  const double angle = 0.7;
  e.pose_a.position_m = {0.2, -0.1, 0.3};
  e.pose_a.orientation_wxyz = {std::cos(angle / 2), 0, 0, std::sin(angle / 2)};
  const std::array<double, 3> dir{0.6, 0.0, 0.8};  // unit, through the centre: no torque
  e.point_m = {0.2 - radius * dir[0], -0.1 - radius * dir[1], 0.3 - radius * dir[2]};
  const double j = 0.05, tau = 1e-3;
  e.impulse_n_s = {j * dir[0], j * dir[1], j * dir[2]};
  e.sustained = true;  // a contact of given length: the reference needs no Hertz radius
  e.contact_time_s = tau;
  e.where = "pebble-scene: events[0]";
  scene.events.push_back(e);
  scene.listeners_m.push_back({0.2 + 0.6, -0.1 + 0.48, 0.3 + 0.64});  // 1 m away
  scene.duration_s = 0.012;
  synth::RenderOptions options;
  const auto out = synth::render_scene(scene, {&pan}, options);
  EXPECT_EQ(pan.own_entries(), 1u);
  const HalfSine hs{kernels::half_sine_peak(j, tau) / pebble.mass_kg, e.t_s, tau};
  const double cos_theta = 0.6 * dir[0] + 0.48 * dir[1] + 0.64 * dir[2];
  const double err = relative_l2(out[0][0], [&](std::size_t n) {
    return reference::translating_sphere_pressure(radius, header.c_m_s, header.rho_kg_m3, 1.0, cos_theta,
                                                  static_cast<double>(n) / options.rate_hz, half_sine_acceleration, &hs, e.t_s,
                                                  e.t_s + tau, 8);
  });
  std::printf("synth: the pebble with its own PAN (r = 0.1 m, tau = 1 ms) at 1 m: relative L2 %.4f vs the exact translating "
              "sphere\n", err);
  EXPECT_LT(err, 0.02);  // measured 0.81 % (the proxy path of the test above: 1.3 %)
  // Without its mesh the object has no entry, and no proxy bank was given: refused, named.
  scene.objects.front().mesh = nullptr;
  EXPECT_THROW(synth::render_scene(scene, {&pan}, options), InputError);
}

// A sustained contact longer than max_sustained_s adds nothing and is counted; a shorter one, or
// any with the limit raised, sounds (as a half-sine of its own length).
TEST(Synth, LongSustainedContactsAreSkippedAndCounted) {
  ASSERT_FALSE(bank_path.empty()) << "usage: clatter-synth-tests PAN.h5 [MODAL.h5]";
  synth::PanSource pan(bank_path);
  const double radius = 0.1;
  io::Scene scene = one_sphere_scene("sustained-scene", radius);
  const double mass = scene.objects.front().mass_kg;
  io::SceneEvent impact;
  impact.t_s = 0.002;
  impact.a = 1;
  impact.pose_a.position_m = {0, 0, radius};
  impact.point_m = {0, 0, 0};
  impact.impulse_n_s = {0, 0, 0.05};
  impact.normal_speed_m_s = 1.0;
  impact.where = "sustained-scene: events[0]";
  io::SceneEvent resting = impact;
  resting.t_s = 0.004;
  resting.normal_speed_m_s = 0;
  resting.sustained = true;
  resting.contact_time_s = 0.05;
  resting.impulse_n_s = {0, 0, mass * 9.81 * resting.contact_time_s};
  resting.where = "sustained-scene: events[1]";
  scene.listeners_m.push_back({0.6, 0.5, 0.7});
  scene.duration_s = 0.08;
  scene.events = {impact};
  const auto alone = synth::render_scene(scene, {&pan}, {});
  scene.events = {impact, resting};
  synth::RenderStats stats;
  const auto skipped = synth::render_scene(scene, {&pan}, {}, &stats);
  EXPECT_EQ(skipped, alone) << "a 50 ms sustained contact is skipped at the default 10 ms limit";
  EXPECT_EQ(stats.skipped_sustained, 1u);
  EXPECT_EQ(stats.impacts, 1u);
  synth::RenderOptions all;
  all.max_sustained_s = 1.0;
  const auto rendered = synth::render_scene(scene, {&pan}, all, &stats);
  EXPECT_NE(rendered, alone);
  EXPECT_EQ(stats.skipped_sustained, 0u);
  EXPECT_EQ(stats.sustained_impacts, 1u);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (argc > 1) test::pan_bank_path = argv[1];
  if (argc > 2) test::modal_bank_path = argv[2];
  if (argc > 4) test::object_pan_path = argv[3], test::object_pan_mesh_path = argv[4];
  return RUN_ALL_TESTS();
}
