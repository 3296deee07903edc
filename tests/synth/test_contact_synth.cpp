// Contact from the object's own mesh (docs/synth.md "Contact"), through the scene reader and the
// render loop: the Hertz time every source receives, against closed-form Hertz,
//   tau = 2.868 (m^2 / (R E*^2 v))^(1/5),  1/E* = 2 (1 - nu^2) / E (granite on granite),
// with R the sphere's radius for an icosphere mesh, and the rule's radii (r_eq = (3 V / 4 pi)^(1/3),
// r_min = 0.02 r_eq, R_flat = r_eq for a cube, whose proxy is that sphere) for a cube's face, edge
// and corner. No bank file: a source that records the impacts stands in for PAN, modal and ground.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "synth/load_scene.hpp"
#include "synth/render_scene.hpp"
#include "tests/unit/test_meshes.hpp"

using namespace clatter;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kYoungs = 5e10, kPoisson = 0.25, kDensity = 2700;  // granite, object and ground

// Every impact's object and Hertz time, as PAN, modal and ground sound would get them.
class Recorder : public synth::SoundSource {
 public:
  std::string name() const override { return "recorder"; }
  void add(const synth::Impact& im, const std::vector<Vec3>&, int, std::vector<std::vector<double>>&) override {
    ids.push_back(im.model->object->id);
    taus_s.push_back(im.tau_s);
  }
  std::vector<int> ids;
  std::vector<double> taus_s;
};

double hertz_s(double mass_kg, double radius_m, double speed_m_s) {
  const double e_star = kYoungs / (2 * (1 - kPoisson * kPoisson));
  return 2.868 * std::pow(mass_kg * mass_kg / (radius_m * e_star * e_star * speed_m_s), 0.2);
}

struct Drop {
  int id;
  Quaternion orientation;
  Vec3 arm_m;  // the contact point from the centre of mass, body frame
};

// A ground impact at 1 m/s for each drop: the body placed so that its contact point is at z = 0.
std::string event_json(const Drop& d, double t_s) {
  const Vec3 arm = rotate(d.orientation, d.arm_m);
  const Vec3 position{0.3 * d.id, 0.1, -arm[2]};
  const Vec3 point = add(position, arm);
  std::ostringstream s;
  s.precision(17);
  s << "{\"t_s\": " << t_s << ", \"a\": " << d.id << ", \"b\": \"ground\", \"point_m\": [" << point[0] << ", " << point[1]
    << ", " << point[2] << "], \"impulse_n_s\": [0, 0, 1], \"normal_speed_m_s\": 1, \"pose_a\": {\"position_m\": ["
    << position[0] << ", " << position[1] << ", " << position[2] << "], \"orientation_wxyz\": [" << d.orientation[0] << ", "
    << d.orientation[1] << ", " << d.orientation[2] << ", " << d.orientation[3] << "]}}";
  return s.str();
}

Quaternion about(Vec3 axis, double angle_rad) {
  const double n = std::sqrt(dot(axis, axis)), s = std::sin(angle_rad / 2);
  return {std::cos(angle_rad / 2), s * axis[0] / n, s * axis[1] / n, s * axis[2] / n};
}

// Writes the meshes and a scene (objects: 1 a 0.1 m icosphere of 5120 triangles, 2 a 0.1 m cube
// mesh whose faces are 2 x 2 squares, 3 the same cube given by numbers) with the drops, then loads
// and renders it; the Hertz time of each impact in order.
std::vector<double> render_drops(const std::vector<Drop>& drops, Recorder& rec, synth::RenderStats* stats = nullptr) {
  const auto dir = std::filesystem::temp_directory_path() / "clatter-contact-synth";
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(test::write_obj(test::icosphere(0.1, 4, {1, 2, 3}), (dir / "sphere.obj").string()));  // off the origin: the body frame is the centre's
  EXPECT_TRUE(test::write_obj(test::box({0.1, 0.1, 0.1}, 2), (dir / "cube.obj").string()));
  const double side = 0.1, mass = kDensity * side * side * side, moment = mass * side * side / 6;
  std::ostringstream s;
  s.precision(17);
  s << "{\"format\": \"clatter-scene\", \"format_version\": 1, \"materials\": {\"granite\": {\"youngs_modulus_pa\": " << kYoungs
    << ", \"poisson_ratio\": " << kPoisson << "}}, \"ground_material\": \"granite\", \"objects\": ["
    << "{\"id\": 1, \"mesh\": \"sphere.obj\", \"density_kg_m3\": " << kDensity << ", \"material\": \"granite\"}, "
    << "{\"id\": 2, \"mesh\": \"cube.obj\", \"density_kg_m3\": " << kDensity << ", \"material\": \"granite\"}, "
    << "{\"id\": 3, \"mass_kg\": " << mass << ", \"volume_m3\": " << side * side * side << ", \"inertia_kg_m2\": [[" << moment
    << ", 0, 0], [0, " << moment << ", 0], [0, 0, " << moment << "]], \"material\": \"granite\"}], \"events\": [";
  for (std::size_t k = 0; k < drops.size(); ++k) s << (k ? ", " : "") << event_json(drops[k], 0.01 * static_cast<double>(k + 1));
  s << "], \"listeners\": [{\"position_m\": [0, 2, 1]}], \"duration_s\": 0.2}";
  std::ofstream((dir / "scene.json").string()) << s.str();
  const io::Scene scene = synth::load_scene((dir / "scene.json").string());
  synth::RenderOptions options;
  options.rate_hz = 8000;
  synth::render_scene(scene, {&rec}, options, stats);
  return rec.taus_s;
}

}  // namespace

// An icosphere mesh (5120 triangles) hit anywhere: the sphere's Hertz time, mass and radius
// analytic, to 1 %.
TEST(ContactSynth, SphereMeshGivesTheSpheresHertzTime) {
  const double radius = 0.1, mass = kDensity * 4 * kPi / 3 * radius * radius * radius;
  std::vector<Drop> drops;
  const Quaternion turned = about({1, 2, -0.5}, 0.9);
  for (const Vec3& d : std::vector<Vec3>{{0, 0, -1}, {0.6, 0, -0.8}, {0.36, 0.48, -0.8}, {-0.48, 0.6, -0.64}})
    drops.push_back({1, turned, scale(d, radius)});
  Recorder rec;
  synth::RenderStats stats;
  const auto taus = render_drops(drops, rec, &stats);
  ASSERT_EQ(taus.size(), drops.size());
  EXPECT_EQ(stats.mesh_contacts, (std::array<std::size_t, 3>{4, 0, 0}));  // all smooth
  const double expected = hertz_s(mass, radius, 1.0);
  for (const double tau : taus) {
    std::printf("icosphere: tau %.3f us, the sphere's %.3f us, error %+.3f %%\n", tau * 1e6, expected * 1e6, 100 * (tau / expected - 1));
    EXPECT_NEAR(tau / expected, 1, 0.01);
  }
}

// A 10 cm granite cube mesh dropped at 1 m/s onto granite, on a face, an edge and a corner: three
// times by the rule (docs/synth.md quotes them), corner > edge > face; the same cube given by numbers
// keeps its proxy sphere's time wherever it is hit.
TEST(ContactSynth, CubeFaceEdgeAndCornerTimes) {
  const double side = 0.1, h = side / 2, mass = kDensity * side * side * side;
  const double r_eq = std::cbrt(3 * side * side * side / (4 * kPi)), r_min = 0.02 * r_eq;
  const Quaternion level{1, 0, 0, 0};
  const Quaternion on_edge = about({1, 0, 0}, kPi / 4);               // the edge x along, y = z = -h, lowest
  const Quaternion on_corner = about({1, -1, 0}, std::atan(std::sqrt(2.0)));  // the corner (-h, -h, -h) lowest
  const std::vector<Drop> drops{{2, level, {0, 0, -h}}, {2, on_edge, {0.01, -h, -h}}, {2, on_corner, {-h, -h, -h}},
                                {3, level, {0, 0, -h}}, {3, on_corner, {-h, -h, -h}}};
  Recorder rec;
  synth::RenderStats stats;
  const auto taus = render_drops(drops, rec, &stats);
  ASSERT_EQ(taus.size(), drops.size());
  EXPECT_EQ(stats.mesh_contacts, (std::array<std::size_t, 3>{1, 1, 1}));  // object 3 has no mesh
  const double face = hertz_s(mass, r_eq, 1.0), edge = hertz_s(mass, std::sqrt(r_min * r_eq), 1.0), corner = hertz_s(mass, r_min, 1.0);
  std::printf("10 cm granite cube at 1 m/s on granite: face %.1f us, edge %.1f us, corner %.1f us (rule: %.1f, %.1f, %.1f)\n",
              taus[0] * 1e6, taus[1] * 1e6, taus[2] * 1e6, face * 1e6, edge * 1e6, corner * 1e6);
  EXPECT_NEAR(taus[0] / face, 1, 1e-9);
  EXPECT_NEAR(taus[1] / edge, 1, 1e-9);
  EXPECT_NEAR(taus[2] / corner, 1, 1e-9);
  EXPECT_NEAR(taus[3] / face, 1, 1e-9);  // by numbers: the proxy sphere r_eq, face or corner alike
  EXPECT_NEAR(taus[4] / face, 1, 1e-9);
}

// A contact point half the cube's reach from its surface: the mesh and the scene disagree (another
// frame, other units); an error naming the event, not a guess.
TEST(ContactSynth, ContactFarFromTheMeshIsAnError) {
  Recorder rec;
  try {
    render_drops({{2, {1, 0, 0, 0}, {0, 0, -0.1}}}, rec);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("events[0]"), std::string::npos) << what;
    EXPECT_NE(what.find("object 2"), std::string::npos) << what;
    EXPECT_NE(what.find("from the mesh's surface"), std::string::npos) << what;
  }
}
