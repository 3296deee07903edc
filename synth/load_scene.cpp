#include "synth/load_scene.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "kernels/mass_properties.hpp"

namespace clatter::synth {

void resolve_mesh_object(io::SceneObject& o) {
  io::TriangleMesh mesh;
  try {
    mesh = io::read_obj(o.mesh_path);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}.mesh: {}", o.where, e.what()));
  }
  const auto props = kernels::mesh_mass_properties(mesh.vertices_m, mesh.triangles);
  if (!(props.volume_m3 > 0))
    throw InputError(fmt::format("{}.mesh: {} encloses a signed volume of {} m^3: faces must wind counter-clockwise seen from outside",
                                 o.where, o.mesh_path, props.volume_m3));
  const double density = o.density_kg_m3 > 0 ? o.density_kg_m3 : o.mass_kg / props.volume_m3;
  o.volume_m3 = props.volume_m3;
  o.mass_kg = density * props.volume_m3;
  o.rest_centre_m = props.centroid_m;
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) o.inertia_kg_m2[r][c] = density * props.inertia_per_density_m5[r][c];
}

io::Scene load_scene(const std::string& scene_path, const std::string& impulses_path) {
  io::Scene scene = io::read_scene(scene_path, impulses_path.empty());
  for (auto& o : scene.objects)
    if (!o.mesh_path.empty()) resolve_mesh_object(o);
  // Rest-pose contact points need the centres of mass, hence after the meshes.
  if (!impulses_path.empty()) io::read_impulse_events(impulses_path, scene);
  return scene;
}

}  // namespace clatter::synth
