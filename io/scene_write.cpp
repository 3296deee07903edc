// The native scene writer (docs/scene-format.md): what clatter-sim produces, read back by
// io/scene.cpp's read_scene.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "core/cleanup.hpp"
#include "core/errors.hpp"
#include "io/content_hash.hpp"
#include "io/mesh.hpp"
#include "io/scene.hpp"
#include "io/text_file.hpp"

namespace clatter::io {
namespace {

using nlohmann::ordered_json;

ordered_json pose_json(const Pose& p) { return {{"position_m", p.position_m}, {"orientation_wxyz", p.orientation_wxyz}}; }

ordered_json material_json(const model::Material& m) {
  ordered_json j = {{"youngs_modulus_pa", m.youngs_pa}, {"poisson_ratio", m.poisson}};
  if (m.damping) j["rayleigh_alpha_1_s"] = m.damping->alpha_1_s, j["rayleigh_beta_s"] = m.damping->beta_s;
  if (m.rho_kg_m3 > 0) j["density_kg_m3"] = m.rho_kg_m3;
  return j;
}

// `mesh`: the object's OBJ path relative to the scene's folder, empty for an object given by numbers.
ordered_json object_json(const SceneObject& o, const std::string& mesh) {
  ordered_json j = {{"id", o.id}};
  if (mesh.empty())
    j.update({{"mass_kg", o.mass_kg}, {"volume_m3", o.volume_m3}, {"inertia_kg_m2", o.inertia_kg_m2}});
  else
    j.update({{"mesh", mesh}, {"mass_kg", o.mass_kg}});  // the reader takes volume and inertia from the mesh
  j.update({{"material", o.material}, {"created_s", o.created_s}});
  j["destroyed_s"] = std::isfinite(o.destroyed_s) ? ordered_json(o.destroyed_s) : ordered_json(nullptr);
  if (o.base_frequency_hz > 0) j["base_frequency_hz"] = o.base_frequency_hz;
  return j;
}

ordered_json event_json(const SceneEvent& e) {
  ordered_json j = {{"t_s", e.t_s}, {"a", e.a}};
  j["b"] = e.fracture ? ordered_json("fracture") : e.b == 0 ? ordered_json("ground") : ordered_json(e.b);
  j["point_m"] = e.point_m;
  j["impulse_n_s"] = e.impulse_n_s;
  if (e.fracture || e.sustained)
    j["contact_time_s"] = e.contact_time_s;
  else
    j["normal_speed_m_s"] = e.normal_speed_m_s;
  j["pose_a"] = pose_json(e.pose_a);
  if (e.b != 0) j["pose_b"] = pose_json(e.pose_b);
  return j;
}

// One list item per line: scenes diff line by line under version control.
void write_list(std::ostream& out, const char* key, const std::vector<ordered_json>& items, bool last = false) {
  out << "  \"" << key << "\": [";
  for (std::size_t i = 0; i < items.size(); ++i) out << (i ? ",\n    " : "\n    ") << items[i].dump();
  out << (items.empty() ? "]" : "\n  ]") << (last ? "\n" : ",\n");
}

std::filesystem::path mesh_folder_of(const std::string& scene_path) {
  std::filesystem::path folder = scene_path;
  if (folder.extension() == ".json") folder.replace_extension();
  return folder += ".meshes";
}

// Each mesh object's OBJ in the scene's mesh folder, named ID-HASH.obj by its text's hash, so a run
// never overwrites a file the scene already there names with other content: until the new scene is
// renamed into place, the old one and its meshes stay consistent. Returns id -> path relative to
// the scene's folder.
std::map<int, std::string> write_meshes(const Scene& scene, const std::string& scene_path) {
  std::map<int, std::string> paths;
  std::filesystem::path folder;
  for (const auto& o : scene.objects) {
    if (!o.mesh) {
      if (!o.mesh_path.empty()) throw std::logic_error("write_scene: an object given by a mesh file must be loaded first");
      continue;
    }
    if (folder.empty()) {
      folder = scene_mesh_folder(scene_path);
      std::filesystem::create_directories(folder);
    }
    const std::string text = obj_text(*o.mesh);
    const std::string name = fmt::format("{}-{}.obj", o.id, hash_hex(text_hash(text)));
    write_text_file((folder / name).string(), text, "mesh");
    paths[o.id] = folder.filename().string() + "/" + name;
  }
  return paths;
}

// After the new scene is in place: the mesh files of earlier scenes at this path (named as
// write_meshes names them) that it does not name. Nothing else in the folder is touched.
void remove_stale_meshes(const std::string& scene_path, const std::map<int, std::string>& kept) {
  const std::filesystem::path folder = mesh_folder_of(scene_path);
  if (!std::filesystem::is_directory(folder)) return;
  std::set<std::string> names;
  for (const auto& [id, path] : kept) names.insert(std::filesystem::path(path).filename().string());
  static const std::regex ours("[0-9]+-[0-9a-f]{16}\\.obj");
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && std::regex_match(name, ours) && !names.count(name)) std::filesystem::remove(entry.path());
  }
}

}  // namespace

std::string scene_mesh_folder(const std::string& scene_path) {
  const std::filesystem::path folder = mesh_folder_of(scene_path);
  if (std::filesystem::exists(folder) && !std::filesystem::is_directory(folder))
    throw InputError(fmt::format("{}: exists and is not a folder: the scene's meshes go there (move it, or choose another output)",
                                 folder.string()));
  return folder.string();
}

void write_scene(const Scene& scene, const std::string& path, const std::string& generator_json) {
  ordered_json materials = ordered_json::object();
  for (const auto& [name, m] : scene.materials) materials[name] = material_json(m);
  std::vector<ordered_json> objects, events, listeners;
  const std::map<int, std::string> meshes = write_meshes(scene, path);
  for (const auto& o : scene.objects) objects.push_back(object_json(o, meshes.count(o.id) ? meshes.at(o.id) : ""));
  for (const auto& e : scene.events) events.push_back(event_json(e));
  for (const auto& l : scene.listeners_m) listeners.push_back({{"position_m", l}});
  std::vector<ordered_json> fractures;
  for (const auto& f : scene.fractures)
    fractures.push_back({{"t_s", f.t_s}, {"body", f.body}, {"pieces", f.pieces}, {"max_principal_pa", f.max_principal_pa},
                         {"strength_pa", f.strength_pa}, {"toughness_j_m2", f.toughness_j_m2},
                         {"strain_energy_j", f.strain_energy_j}, {"fracture_area_m2", f.fracture_area_m2},
                         {"fracture_energy_j", f.fracture_energy_j}, {"kinetic_energy_gained_j", f.kinetic_energy_gained_j},
                         {"tau_s", f.tau_s}, {"tets", f.tets}});
  const std::string temp = path + ".partial";
  register_temporary(temp);
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot create the scene file");
    out << "{\n  \"format\": \"clatter-scene\", \"format_version\": 1,\n";
    out << "  \"generator\": " << ordered_json::parse(generator_json).dump() << ",\n";
    out << "  \"materials\": " << materials.dump() << ",\n";
    out << "  \"ground_material\": " << ordered_json(scene.ground_material).dump() << ",\n";
    if (scene.duration_s > 0) out << "  \"duration_s\": " << ordered_json(scene.duration_s).dump() << ",\n";
    write_list(out, "listeners", listeners);
    write_list(out, "objects", objects);
    if (!fractures.empty()) write_list(out, "fractures", fractures);
    write_list(out, "events", events, true);
    out << "}\n";
    out.flush();
    if (!out) throw std::runtime_error(path + ": writing the scene failed (disk full?)");
  }
  std::filesystem::rename(temp, path);
  unregister_temporary(temp);
  remove_stale_meshes(path, meshes);
}

}  // namespace clatter::io
