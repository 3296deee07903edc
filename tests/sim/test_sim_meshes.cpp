// The meshes clatter-sim writes beside its scene (docs/scene-format.md, "Scenes written by
// clatter-sim"): each is closed and consistently oriented; read back by clatter-synth's loader its
// volume times the material's density is the scene's mass and its inertia the simulator's
// principal moments; placed by an event's pose it is where Bullet's contact was; and rewriting a
// scene replaces only the mesh files it wrote.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "io/materials.hpp"
#include "io/mesh.hpp"
#include "sim/simulate.hpp"
#include "synth/load_scene.hpp"
#include "tests/reference/surfaces.hpp"

namespace clatter::sim {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("clatter-sim-meshes-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Every directed edge once, and its reverse once: closed, manifold, consistently oriented
// (independent of io::read_obj's own check).
bool closed_and_oriented(const io::TriangleMesh& m) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  return std::all_of(edges.begin(), edges.end(), [&](const auto& e) {
    const auto back = edges.find({e.first.second, e.first.first});
    return e.second == 1 && back != edges.end() && back->second == 1;
  });
}

// A point's signed distance to a convex mesh's surface, as the largest of its face planes'
// (exact for points whose nearest feature is a face; near an edge it underestimates outside).
double convex_distance_m(const io::TriangleMesh& m, const Vec3& q) {
  double d = -INFINITY;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices_m[t[0]], &b = m.vertices_m[t[1]], &c = m.vertices_m[t[2]];
    Vec3 n = cross(sub(b, a), sub(c, a));
    n = scale(n, 1 / std::sqrt(dot(n, n)));
    d = std::max(d, dot(n, sub(q, a)));
  }
  return d;
}

// World -> the mesh's coordinates for an object posed by its centre of mass and orientation.
Vec3 to_mesh(const io::Pose& pose, const io::SceneObject& o, const Vec3& world_m) {
  return add(rotate_inverse(pose.orientation_wxyz, sub(world_m, pose.position_m)), o.rest_centre_m);
}

TEST(SimMeshes, PlateAndPiecesAreTheSimulatedSolids) {
  io::Config c(sim_schema());
  c.set("plate.pieces=12");
  c.set("sim.duration_s=0.45");
  c.set("bodies.base_frequency=false");
  const io::Scene simulated = simulate(c, "");
  const fs::path path = scratch("plate") / "plate.json";
  io::write_scene(simulated, path.string());
  const io::Scene read = synth::load_scene(path.string());
  ASSERT_EQ(read.objects.size(), 13u);
  const double rho = io::find_material(io::builtin_materials(), "ceramic", "").rho_kg_m3;
  std::map<int, const io::SceneObject*> by_id;
  for (std::size_t i = 0; i < read.objects.size(); ++i) {
    const io::SceneObject &s = simulated.objects[i], &r = read.objects[i];
    by_id[r.id] = &r;
    EXPECT_EQ(fs::path(r.mesh_path).parent_path(), path.parent_path() / "plate.meshes");
    EXPECT_TRUE(closed_and_oriented(io::read_obj(r.mesh_path))) << r.mesh_path;
    EXPECT_LT(std::abs(r.mass_kg / s.mass_kg - 1), 1e-14) << "mass given, rounded through m / V * V";
    EXPECT_LT(std::abs(r.volume_m3 * rho / s.mass_kg - 1), 1e-9) << "object " << r.id;
    const double moment_scale = std::max({s.inertia_kg_m2[0][0], s.inertia_kg_m2[1][1], s.inertia_kg_m2[2][2]});
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        EXPECT_LT(std::abs(r.inertia_kg_m2[k][l] - s.inertia_kg_m2[k][l]), 1e-9 * moment_scale) << "object " << r.id << " I" << k << l;
    // The body frame is centred: poses place the mesh's origin.
    EXPECT_LT(std::sqrt(dot(r.rest_centre_m, r.rest_centre_m)), 1e-12) << "object " << r.id;
  }
  // Bullet's contact points lie on the posed meshes: within its speculative distance and margin
  // (1 mm, corners rounded by it) plus the pieces' gap, against a plate 130 mm across.
  std::size_t contacts = 0;
  double worst_m = 0;
  for (const io::SceneEvent& e : read.events) {
    if (e.fracture) continue;
    for (const auto& [id, pose] : {std::pair{e.a, e.pose_a}, std::pair{e.b, e.pose_b}}) {
      if (id == 0) continue;
      const io::SceneObject& o = *by_id.at(id);
      worst_m = std::max(worst_m, std::abs(convex_distance_m(*o.mesh, to_mesh(pose, o, e.point_m))));
      ++contacts;
    }
  }
  EXPECT_GT(contacts, 20u);
  EXPECT_LT(worst_m, 2.5e-3) << "contact points off their posed meshes";
  std::printf("%zu contact points on the posed meshes: largest distance %.3g mm\n", contacts, 1e3 * worst_m);
}

// An L prism (its principal axes turned against its OBJ's) falling freely: its written mesh,
// placed by its final pose, is its OBJ moved straight down.
TEST(SimMeshes, MeshBodyPosePlacesItsOBJ) {
  const reference::Surface l = reference::l_prism(0.05, 0.02);
  const fs::path dir = scratch("lprism");
  const std::string obj = (dir / "l.obj").string();
  io::TriangleMesh given{l.vertices_m, l.triangles};
  std::ofstream(obj) << io::obj_text(given);
  const Vec3 at{0.3, -0.2, 1.0};
  io::Config c(sim_schema());
  c.set("meshes.files=[\"" + obj + "\"]");
  c.set(fmt::format("meshes.positions_m=[[{},{},{}]]", at[0], at[1], at[2]));
  c.set("sim.duration_s=0.1");
  c.set("bodies.base_frequency=false");
  c.set("sim.bodies=[]");
  SimStats stats;
  const io::Scene simulated = simulate(c, "", &stats);
  io::write_scene(simulated, (dir / "l.json").string());
  const io::Scene read = synth::load_scene((dir / "l.json").string());
  ASSERT_EQ(read.objects.size(), 1u);
  const io::SceneObject& o = read.objects[0];
  const io::Pose& pose = stats.final_states.at(o.id).pose;
  const Quaternion q = pose.orientation_wxyz;
  EXPECT_GT(std::abs(q[1]) + std::abs(q[2]) + std::abs(q[3]), 0.1) << "the body frame should be turned against the OBJ's axes";
  const Vec3 drop = sub(add(rotate(pose.orientation_wxyz, sub(o.mesh->vertices_m[0], o.rest_centre_m)), pose.position_m), given.vertices_m[0]);
  double worst_m = 0;
  for (std::size_t i = 0; i < given.vertices_m.size(); ++i) {
    const Vec3 world = add(rotate(pose.orientation_wxyz, sub(o.mesh->vertices_m[i], o.rest_centre_m)), pose.position_m);
    const Vec3 d = sub(sub(world, given.vertices_m[i]), drop);
    worst_m = std::max(worst_m, std::sqrt(dot(d, d)));
  }
  EXPECT_LT(worst_m, 1e-12) << "the posed mesh is the OBJ translated";
  EXPECT_NEAR(drop[0], at[0], 1e-12);
  EXPECT_NEAR(drop[1], at[1], 1e-12);
  const double t = 0.1, dt = c.real("sim.dt_s"), g = c.real("sim.gravity_m_s2");
  EXPECT_NEAR(drop[2], at[2] - g * t * t / 2, g * t * dt) << "free fall";
}

io::Scene two_boxes(double size_m) {
  io::Scene s;
  s.materials["m"] = io::builtin_materials().front();
  s.materials["m"].source.clear();
  s.ground_material = "m";
  s.listeners_m = {{0, 0, 1}};
  for (int id : {1, 2}) {
    const reference::Surface b = reference::box(size_m * id, size_m, size_m);
    io::SceneObject o;
    o.id = id, o.mass_kg = 1, o.material = "m";
    o.mesh = std::make_shared<const io::TriangleMesh>(io::TriangleMesh{b.vertices_m, b.triangles});
    s.objects.push_back(o);
  }
  return s;
}

// A rewrite removes the earlier scene's mesh files, never a file it did not write; a file where
// the mesh folder goes is refused before anything is written.
TEST(SimMeshes, RewriteRemovesOnlyItsOwnMeshes) {
  const fs::path dir = scratch("rewrite");
  const std::string path = (dir / "s.json").string();
  io::write_scene(two_boxes(0.1), path);
  const io::Scene first = io::read_scene(path);
  std::ofstream(dir / "s.meshes" / "mine.obj") << "a user's file\n";
  std::ofstream(dir / "s.meshes" / "notes.txt") << "a user's file\n";
  io::write_scene(two_boxes(0.2), path);
  const io::Scene second = io::read_scene(path);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NE(first.objects[i].mesh_path, second.objects[i].mesh_path) << "new content, new name";
    EXPECT_FALSE(fs::exists(first.objects[i].mesh_path)) << "the earlier scene's meshes are removed";
    EXPECT_TRUE(fs::is_regular_file(second.objects[i].mesh_path));
  }
  EXPECT_TRUE(fs::exists(dir / "s.meshes" / "mine.obj"));
  EXPECT_TRUE(fs::exists(dir / "s.meshes" / "notes.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "s.meshes"), fs::directory_iterator{}), 4);

  const std::string blocked = (dir / "t.json").string();
  std::ofstream(blocked) << "a scene the user had\n";
  std::ofstream(dir / "t.meshes") << "not a folder\n";
  EXPECT_THROW(io::write_scene(two_boxes(0.1), blocked), InputError);
  std::ifstream kept(blocked);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "a scene the user had\n");
  EXPECT_FALSE(fs::exists(blocked + ".partial"));
}

}  // namespace
}  // namespace clatter::sim
