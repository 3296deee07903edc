#include "synth/load_scene.hpp"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "io/mesh.hpp"
#include "kernels/fem/lowest_mode.hpp"
#include "kernels/mass_properties.hpp"

namespace clatter::synth {
namespace {

struct Solid {
  std::shared_ptr<const io::TriangleMesh> mesh;
  kernels::MeshMassProperties props;
};

// The uniform solid a mesh file bounds; `where` names the object for messages.
Solid solid_of(const std::string& mesh_path, const std::string& where) {
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
  return {std::make_shared<const io::TriangleMesh>(std::move(mesh)), props};
}

// omega_0 of the object's solid in its material, computed once per mesh file and material.
double base_frequency_hz(const io::Scene& scene, const io::SceneObject& o, const io::TriangleMesh& mesh,
                         std::map<std::tuple<std::string, double, double, double>, double>& cache) {
  const model::Material& m = scene.materials.at(o.material);
  const double rho = o.mass_kg / o.volume_m3;
  const auto key = std::make_tuple(o.mesh_path, m.youngs_pa, m.poisson, rho);
  const auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  try {
    const double f = kernels::fem::lowest_free_mode(mesh.vertices_m, mesh.triangles, m.youngs_pa, m.poisson,
                                                    rho).frequency_hz;
    return cache[key] = f;
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("{}.mesh: {}: its lowest mode: {}", o.where, o.mesh_path, e.what()));
  }
}

void set_mass_properties(io::SceneObject& o, const kernels::MeshMassProperties& solid) {
  const double density = o.density_kg_m3 > 0 ? o.density_kg_m3 : o.mass_kg / solid.volume_m3;
  o.volume_m3 = solid.volume_m3;
  o.mass_kg = density * solid.volume_m3;
  o.rest_centre_m = solid.centroid_m;
  o.surface_area_m2 = solid.surface_area_m2;
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) o.inertia_kg_m2[r][c] = density * solid.inertia_per_density_m5[r][c];
}

}  // namespace

void resolve_meshes(io::Scene& scene) {
  std::map<std::string, Solid> solids;  // debris often shares a few meshes
  for (auto& o : scene.objects) {
    if (o.mesh_path.empty() || o.mesh) continue;
    auto it = solids.find(o.mesh_path);
    if (it == solids.end()) it = solids.emplace(o.mesh_path, solid_of(o.mesh_path, o.where)).first;
    set_mass_properties(o, it->second.props);
    o.mesh = it->second.mesh;
  }
}

void add_base_frequencies(io::Scene& scene) {
  std::map<std::tuple<std::string, double, double, double>, double> frequencies;
  for (auto& o : scene.objects) {
    if (!o.mesh || o.base_frequency_hz > 0) continue;
    o.base_frequency_hz = base_frequency_hz(scene, o, *o.mesh, frequencies);
    o.base_frequency_from = "mesh";
  }
}

io::Scene load_scene(const std::string& scene_path, const std::string& impulses_path, bool base_frequencies) {
  Stage stage("scene");
  io::Scene scene = io::read_scene(scene_path, impulses_path.empty());
  resolve_meshes(scene);
  if (base_frequencies) add_base_frequencies(scene);
  // Rest-pose contact points need the centres of mass, hence after the meshes.
  if (!impulses_path.empty()) io::read_impulse_events(impulses_path, scene);
  return scene;
}

}  // namespace clatter::synth
