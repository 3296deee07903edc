#pragma once
// A scene for clatter-synth (format "clatter-scene" v1, JSON, docs/scene-format.md): objects with
// their mass properties and materials, the impulses between them or with the ground, listeners.
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/mesh.hpp"
#include "model/material.hpp"

namespace clatter::io {

// A scene's materials are model::Material, keyed by name (the JSON keys youngs_modulus_pa,
// poisson_ratio, density_kg_m3 and the Rayleigh pair, docs/scene-format.md). Optional there: the
// Rayleigh damping (only modal sound needs it; clatter-synth refuses a modal object without it)
// and the density (rho_kg_m3 = 0: not given; only the ground sound needs the ground's, and takes
// the ground bank's when the scene gives none). `source` is empty.

struct SceneObject {
  int id = 0;
  double mass_kg = 0, volume_m3 = 0;
  std::array<std::array<double, 3>, 3> inertia_kg_m2{};  // body frame, about the centre of mass
  std::string material;
  // Given by a closed triangle mesh instead: its OBJ path, and the density unless mass_kg is
  // given; synth::load_scene then fills in mass, volume, inertia and rest_centre_m.
  std::string mesh_path;
  double density_kg_m3 = 0;
  // The mesh itself, once synth::load_scene has read it (objects of one file share it), in its own
  // frame: contact takes the local curvature from it. Null for objects given by numbers. A writer
  // (clatter-sim) sets it, with mesh_path empty, for write_scene to write the OBJ.
  std::shared_ptr<const TriangleMesh> mesh;
  double surface_area_m2 = 0;  // the mesh's, once synth::load_scene has read it (0: no mesh)
  // The centre of mass in the rest-pose coordinates (the mesh's; 0 for objects given by numbers),
  // about which the James-lab format's rest-pose contact points are taken.
  std::array<double, 3> rest_centre_m{};
  std::string where;  // "FILE: objects[i]", for messages
  // The lowest free-vibration frequency, when the simulator knows it (0: not given; clatter-synth
  // then computes it from the mesh or the proxy, docs/synth.md).
  double base_frequency_hz = 0;
  std::string base_frequency_from;  // "scene" when given, "mesh" when computed from the mesh
  double created_s = 0, destroyed_s = std::numeric_limits<double>::infinity();
};

struct Pose {
  std::array<double, 3> position_m{};             // centre of mass, world frame
  std::array<double, 4> orientation_wxyz{1, 0, 0, 0};  // unit quaternion, body -> world
};

struct SceneEvent {
  double t_s = 0;
  int a = 0, b = 0;                     // object ids; b = 0: the ground
  std::array<double, 3> point_m{};      // contact point, world frame
  std::array<double, 3> impulse_n_s{};  // impulse on a (b receives its opposite), world frame
  double normal_speed_m_s = 0;          // relative normal speed at contact
  // A fracture impulse (003 section 3.3): the piece a is pushed off its parent by the released
  // strain energy over contact_time_s (003 eq. 5's tau) instead of a Hertz contact; b is 0.
  bool fracture = false;
  // A sustained contact (resting, sliding, rolling): a force that lasted contact_time_s, whose
  // duration the simulator knows, instead of an impact whose Hertz duration follows from the
  // normal speed. Rendered as a half-sine of that length, like a fracture impulse.
  bool sustained = false;
  double contact_time_s = 0;
  Pose pose_a, pose_b;
  std::string where;                    // "FILE: events[i]" or "FILE:line", for messages
};

// What the simulator did at one fracture (003 section 3), for the reader of a scene: the energy
// budget that decided the pieces. clatter-synth does not read it (the events carry the sound).
struct SceneFracture {
  double t_s = 0;
  int body = 0;                 // the object that broke
  std::vector<int> pieces;      // the objects it became
  double max_principal_pa = 0;  // the largest principal stress at the step (Rankine)
  double strength_pa = 0, toughness_j_m2 = 0;
  double strain_energy_j = 0;   // E_S of the quasistatic solve
  double fracture_area_m2 = 0;  // A_F
  double fracture_energy_j = 0; // E_F = G_c A_F <= eta E_S
  double kinetic_energy_gained_j = 0;  // Delta E_K = E_S - E_F when fracture impulses are on, else 0
  double tau_s = 0;             // the fracture impulses' duration (003 eq. 5)
  std::size_t tets = 0;         // of the broken body's stress mesh
};

struct Scene {
  std::string path;  // for messages
  std::map<std::string, model::Material> materials;
  std::string ground_material;
  std::vector<SceneObject> objects;
  std::vector<SceneEvent> events;  // sorted by time
  std::vector<SceneFracture> fractures;  // written by write_scene, not read back (read_scene skips it)
  std::vector<std::array<double, 3>> listeners_m;
  double duration_s = 0;           // 0: until the last event's sound has died out
};

// Reads and validates a scene (without its events, for the side file of an impulse file);
// InputError names the file, the JSON path and the value.
Scene read_scene(const std::string& path, bool read_events = true);
// The same from the scene's text (the Python module's scenes): `path` names it in messages and is
// the folder relative mesh paths start from (its parent; none: the working directory).
Scene parse_scene(const std::string& text, const std::string& path, bool read_events = true);
// Writes a scene in the native JSON form that read_scene reads back, with `generator` (any JSON
// object text, e.g. the simulator and its settings) as an extra top-level key that readers ignore.
// Objects given by numbers are written so; an object that carries its `mesh` is written as a mesh
// object (its mass_kg and the OBJ's path, docs/scene-format.md): the OBJ goes into
// scene_mesh_folder(path) as ID-HASH.obj (HASH: FNV-1a 64 of the OBJ text, io/content_hash.hpp).
// Every file is written to a temporary file and renamed, meshes first, so an existing scene at
// `path` is replaced only by a complete one with all its meshes; then the folder's ID-HASH.obj
// files the new scene does not name are removed (nothing else there is touched). Numbers are
// printed shortest round-trip, so the bytes are a function of the values.
void write_scene(const Scene& scene, const std::string& path, const std::string& generator_json = "{}");
// The folder beside a scene file that holds its objects' meshes: plate.json -> plate.meshes,
// scene -> scene.meshes. InputError if something other than a folder is there.
std::string scene_mesh_folder(const std::string& scene_path);
// Appends the events of a James-lab rigid-body impulse file (one event per line, "C ..." or
// "P ...", docs/scene-format.md) to a scene read from its side file. Rest-pose contact points are
// taken about each object's rest_centre_m, so objects given by meshes must be resolved first.
void read_impulse_events(const std::string& impulse_path, Scene& scene);

}  // namespace clatter::io
