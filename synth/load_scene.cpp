#include "synth/load_scene.hpp"

#include <fmt/format.h>

#include <map>

#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "kernels/mass_properties.hpp"

namespace clatter::synth {
namespace {

// The uniform solid a mesh file bounds; `where` names the object for messages.
kernels::MeshMassProperties solid_of(const std::string& mesh_path, const std::string& where) {
  io::TriangleMesh mesh;
  try {
    mesh = io::read_obj(mesh_path);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}.mesh: {}", where, e.what()));
  }
  const auto props = kernels::mesh_mass_properties(mesh.vertices_m, mesh.triangles);
  if (!(props.volume_m3 > 0))
    throw InputError(fmt::format("{}.mesh: {} encloses a signed volume of {} m^3: faces must wind counter-clockwise seen from outside",
                                 where, mesh_path, props.volume_m3));
  return props;
}

void set_mass_properties(io::SceneObject& o, const kernels::MeshMassProperties& solid) {
  const double density = o.density_kg_m3 > 0 ? o.density_kg_m3 : o.mass_kg / solid.volume_m3;
  o.volume_m3 = solid.volume_m3;
  o.mass_kg = density * solid.volume_m3;
  o.rest_centre_m = solid.centroid_m;
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) o.inertia_kg_m2[r][c] = density * solid.inertia_per_density_m5[r][c];
}

}  // namespace

io::Scene load_scene(const std::string& scene_path, const std::string& impulses_path) {
  io::Scene scene = io::read_scene(scene_path, impulses_path.empty());
  std::map<std::string, kernels::MeshMassProperties> solids;  // debris often shares a few meshes
  for (auto& o : scene.objects) {
    if (o.mesh_path.empty()) continue;
    auto it = solids.find(o.mesh_path);
    if (it == solids.end()) it = solids.emplace(o.mesh_path, solid_of(o.mesh_path, o.where)).first;
    set_mass_properties(o, it->second);
  }
  // Rest-pose contact points need the centres of mass, hence after the meshes.
  if (!impulses_path.empty()) io::read_impulse_events(impulses_path, scene);
  return scene;
}

}  // namespace clatter::synth
