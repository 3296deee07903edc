// The native scene writer (docs/scene-format.md): what clatter-sim produces, read back by
// io/scene.cpp's read_scene.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/cleanup.hpp"
#include "core/errors.hpp"
#include "io/scene.hpp"

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

ordered_json object_json(const SceneObject& o) {
  if (!o.mesh_path.empty()) throw std::logic_error("write_scene: objects must be given by numbers, not meshes");
  ordered_json j = {{"id", o.id}, {"mass_kg", o.mass_kg}, {"volume_m3", o.volume_m3}, {"inertia_kg_m2", o.inertia_kg_m2},
                    {"material", o.material}, {"created_s", o.created_s}};
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

}  // namespace

void write_scene(const Scene& scene, const std::string& path, const std::string& generator_json) {
  ordered_json materials = ordered_json::object();
  for (const auto& [name, m] : scene.materials) materials[name] = material_json(m);
  std::vector<ordered_json> objects, events, listeners;
  for (const auto& o : scene.objects) objects.push_back(object_json(o));
  for (const auto& e : scene.events) events.push_back(event_json(e));
  for (const auto& l : scene.listeners_m) listeners.push_back({{"position_m", l}});
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
    write_list(out, "events", events, true);
    out << "}\n";
    out.flush();
    if (!out) throw std::runtime_error(path + ": writing the scene failed (disk full?)");
  }
  std::filesystem::rename(temp, path);
  unregister_temporary(temp);
}

}  // namespace clatter::io
