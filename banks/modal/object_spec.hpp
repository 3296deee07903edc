#pragma once
// The input contract of `clatter-bank object`, without MPI: its config schema, the validated
// ObjectSpec (the objects: meshes with their materials, from the config's lists or from a scene's
// bodies below the proxy threshold; the band, mesh, solver and transfer settings) and the task list
// it implies, one task per distinct (mesh content, material). In clatter_specs, so a serial tool
// checks an object config exactly as clatter-bank does.
#include <string>
#include <vector>

#include "io/config.hpp"
#include "io/mesh.hpp"
#include "kernels/fem/ellipsoid_mesh.hpp"
#include "model/object_bank.hpp"

namespace clatter::jobs {

const io::Schema& object_schema();

struct ObjectSource {
  std::string mesh_path;          // as given (config) or resolved against the scene's folder
  std::string where;              // "objects.meshes[2]" or "SCENE: objects[7]", for messages
  io::TriangleMesh mesh;          // as read and checked
  std::string mesh_hash;          // io::mesh_hash
  model::Material material;       // with its Rayleigh damping
  double base_frequency_hz = 0;   // from the scene, when it gives one (0: not known)
  std::string key() const { return mesh_hash + "-" + material.name; }
};

struct ObjectSpec {
  model::ObjectBankHeader header;
  std::string material_table;         // where the config's materials came from
  std::vector<ObjectSource> objects;  // one per distinct key, in the order first met
  kernels::fem::EllipsoidMeshBounds bounds;
  // Of a scene: the bodies left to their proxies (omega_0 at or above the threshold) and those that
  // shared another's key, for the sweep's summary.
  std::size_t scene_bodies = 0, scene_above_threshold = 0, scene_duplicates = 0, scene_without_mesh = 0;
};

// Reads every mesh and material and checks every key; InputError naming the file, key and value
// (a mesh that is open, non-manifold, inverted, self-intersecting, degenerate or implausibly large).
ObjectSpec make_object_spec(const io::Config& config);

// The sweep text: the config's TOML plus each object's key, mesh file and resolved material (as
// comments), so an edited mesh or material makes another sweep (io::sweep_id).
std::string object_sweep_toml(const io::Config& config, const ObjectSpec& spec);

struct ObjectTask {
  std::size_t object = 0;
  std::string name;  // the entry's key
};
std::vector<ObjectTask> object_tasks(const ObjectSpec& spec);

}  // namespace clatter::jobs
