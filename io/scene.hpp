#pragma once
// A scene for clatter-synth (format "clatter-scene" v1, JSON, docs/scene-format.md): objects with
// their mass properties and materials, the impulses between them or with the ground, listeners.
#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace clatter::io {

struct SceneMaterial {
  double youngs_modulus_pa = 0, poisson_ratio = 0;
};

struct SceneObject {
  int id = 0;
  double mass_kg = 0, volume_m3 = 0;
  std::array<std::array<double, 3>, 3> inertia_kg_m2{};  // body frame, about the centre of mass
  std::string material;
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
  Pose pose_a, pose_b;
  std::string where;                    // "FILE: events[i]" or "FILE:line", for messages
};

struct Scene {
  std::string path;  // for messages
  std::map<std::string, SceneMaterial> materials;
  std::string ground_material;
  std::vector<SceneObject> objects;
  std::vector<SceneEvent> events;  // sorted by time
  std::vector<std::array<double, 3>> listeners_m;
  double duration_s = 0;           // 0: until the last event's sound has died out
};

// Reads and validates a scene; InputError names the file, the JSON path and the value.
Scene read_scene(const std::string& path);
// Reads a James-lab rigid-body impulse file (one event per line, "C ..." or "P ...") with the
// objects, materials and listeners of a side scene file; docs/scene-format.md.
Scene read_impulse_text(const std::string& impulse_path, const std::string& side_scene_path);

}  // namespace clatter::io
