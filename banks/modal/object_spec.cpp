#include "banks/modal/object_spec.hpp"

#include "banks/modal/modal_spec.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "core/errors.hpp"
#include "io/materials.hpp"
#include "io/scene.hpp"
#include "kernels/fem/lowest_mode.hpp"
#include "kernels/fem/mesh_check.hpp"

namespace clatter::jobs {
namespace {

const model::TransferSettings kTransfer{};

// 003 Table 2 runs its glass slab and windows with omega_proxy between 2000 and 4000 Hz and the
// table at 140-2000 Hz; 2000 Hz is the value three of its four examples use (docs/synth.md
// "Objects with their own models" measures it on Clatter's scenes).
constexpr double kProxyAboveHz = 2000;

constexpr std::size_t kMaxObjects = 10000;

}  // namespace

const io::Schema& object_schema() {
  static const io::Schema schema{
      "clatter-bank object: the object bank (FEM modes and acoustic transfer of given closed meshes)",
      {
          {"objects.meshes", io::StringList{}, "closed triangle meshes (OBJ, metres), one entry each"},
          {"objects.materials", io::StringList{}, "the material of each mesh (a name of material.table); one name "
                                                  "serves them all"},
          {"objects.scene", std::string(""), "a scene (docs/scene-format.md): every object given by a mesh whose lowest "
                                             "frequency is below objects.proxy_above_hz, in its scene material"},
          {"objects.proxy_above_hz", kProxyAboveHz, "omega_proxy / 2 pi of 003 section 5.4: a scene's objects below it "
                                                    "get their own model (clatter-synth --proxy-above-hz)",
           {0.0, 1e6}},
          {"material.table", std::string(""), "materials file (TOML, docs/materials.md); empty: the built-in "
                                              "configs/materials.toml"},
          {"modes.f_max_hz", 20000.0, "keep every mode from f_1 up to this [Hz]", {0.0, 1e6, true}},
          {"modes.cluster_gap", 5e-3, "relative gap below which neighbouring frequencies form one cluster",
           {0.0, 0.1, true}},
          {"mesh.elements_per_wavelength", 3.0, "h = shear wavelength at f_max / this", {1.0, 20.0}},
          {"mesh.elements_through_thickness", std::int64_t{1}, "and h at most the thinnest part / this (1: 10-node "
                                                                "tetrahedra hold pure bending exactly; docs/validation.md)",
           {1, 10}},
          {"mesh.max_radius_edge", 3.0, "largest radius-edge ratio a mesh may have", {1.0, 100.0}},
          {"mesh.min_dihedral_deg", 5.0, "smallest dihedral angle a mesh may have [deg]", {0.0, 60.0}},
          {"mesh.min_jacobian_ratio", 0.2, "smallest min/max det J within a curved element", {0.0, 1.0, true}},
          {"solver.tolerance", 1e-11, "SLEPc's relative convergence tolerance (-eps_tol)", {1e-15, 1e-6}},
          {"solver.residual_limit", 1e-7, "largest relative residual ||Ku - lambda Mu|| / ||Ku|| a mode may have "
                                          "(the ellipsoid bank's 1e-8 is missed by fine meshes of thin parts, at 1.1e-8)",
           {1e-15, 1e-3}},
          {"solver.max_iterations", std::int64_t{0}, "SLEPc restarts per shift; 0: SLEPc's default", {0, 1e6}},
          {"solver.nev_per_shift", std::int64_t{0}, "eigenpairs sought around each shift; 0: SLEPc's default", {0, 1e4}},
          {"medium.c_m_s", kTransfer.sound_speed_m_s, "speed of sound of the air the modes radiate into [m/s]",
           {0.0, 1e5, true}},
          {"medium.rho_kg_m3", kTransfer.air_density_kg_m3, "density of the air [kg/m^3]", {0.0, 1e5, true}},
          {"transfer.sources_per_wavelength", kTransfer.sources_per_wavelength,
           "equivalent sources per air wavelength on their layer", {1.0, 20.0}},
          {"transfer.residual_target", kTransfer.residual_target,
           "boundary residual x normal fraction above which other source layers are tried", {1e-8, 1.0}},
          {"transfer.tail_tolerance", kTransfer.tail_tolerance, "far-field share (L2) the multipole truncation may drop",
           {1e-8, 0.1}},
      }};
  return schema;
}

namespace {

// The mesh read, checked as a solid (kernels/fem/object_mesh.hpp) and plausible in metres at the
// material's density; InputError naming the file and the reason.
ObjectSource read_object(const std::string& path, const std::string& where, const model::Material& material) {
  ObjectSource o;
  o.mesh_path = path;
  o.where = where;
  o.material = material;
  o.mesh = io::read_obj(path);
  try {
    const double volume_m3 = kernels::fem::check_object_surface(o.mesh.vertices_m, o.mesh.triangles);
    // A mesh in millimetres read as metres is a thousand times too large, and its FEM would not
    // fit in memory: refused, not merely warned about.
    const std::string scale = kernels::fem::implausible_scale(o.mesh.vertices_m, volume_m3, material.rho_kg_m3);
    if (!scale.empty()) throw InputError(fmt::format("{}: {}: {}", where, path, scale));
  } catch (const kernels::fem::SurfaceError& e) {
    throw InputError(fmt::format("{}: {}: {}", where, path, e.what()));
  }
  o.mesh_hash = io::mesh_hash(o.mesh);
  return o;
}

void need_damping(const model::Material& m, const std::string& where) {
  if (!m.damping)
    throw InputError(fmt::format("{}: material '{}' has no rayleigh_alpha_1_s and rayleigh_beta_s: a modal model needs "
                                 "its damping",
                                 where, m.name));
}

}  // namespace

ObjectSpec make_object_spec(const io::Config& config) {
  ObjectSpec spec;
  auto& h = spec.header;
  h.f_max_hz = config.real("modes.f_max_hz");
  h.solve = solve_settings(config);
  h.elements_per_wavelength = config.real("mesh.elements_per_wavelength");
  h.elements_through_thickness = static_cast<std::int32_t>(config.integer("mesh.elements_through_thickness"));
  h.proxy_above_hz = config.real("objects.proxy_above_hz");
  h.transfer.method = "equivalent sources on an inner offset of the surface, multipole about the centre of mass "
                      "(docs/transfer.md \"Any closed mesh\")";
  read_transfer_keys(config, h.transfer);
  spec.bounds = mesh_bounds(config);

  std::map<std::string, std::size_t> seen;  // key -> object
  auto add = [&](ObjectSource o) {
    if (seen.emplace(o.key(), spec.objects.size()).second) {
      spec.objects.push_back(std::move(o));
      return true;
    }
    return false;
  };
  const auto& meshes = config.strings("objects.meshes");
  const auto& names = config.strings("objects.materials");
  if (!meshes.empty()) {
    if (names.size() != 1 && names.size() != meshes.size())
      throw InputError(fmt::format("objects.materials: {} names for {} meshes: give one per mesh, or one for all",
                                   names.size(), meshes.size()));
    const auto table = io::read_materials(config.string("material.table"), spec.material_table);
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      const model::Material& m = io::find_material(table, names[names.size() == 1 ? 0 : i], spec.material_table);
      need_damping(m, fmt::format("objects.materials[{}]", names.size() == 1 ? 0 : i));
      if (!add(read_object(meshes[i], fmt::format("objects.meshes[{}]", i), m)))
        throw InputError(fmt::format("objects.meshes[{}] = '{}': the same mesh and material as an earlier entry", i,
                                     meshes[i]));
    }
  } else if (!names.empty()) {
    throw InputError("objects.materials is given but objects.meshes is empty");
  }
  if (const std::string& scene_path = config.string("objects.scene"); !scene_path.empty()) {
    const io::Scene scene = io::read_scene(scene_path, false);
    for (const io::SceneObject& so : scene.objects) {
      ++spec.scene_bodies;
      if (so.mesh_path.empty()) {
        ++spec.scene_without_mesh;
        continue;
      }
      model::Material m = scene.materials.at(so.material);
      need_damping(m, so.where);
      if (!(m.rho_kg_m3 > 0)) m.rho_kg_m3 = so.mass_kg > 0 ? 0 : so.density_kg_m3;
      ObjectSource o = read_object(so.mesh_path, so.where, m);
      if (!(o.material.rho_kg_m3 > 0)) {  // the scene's density is the object's mass over its volume
        const double volume_m3 = kernels::fem::enclosed_volume_m3(o.mesh.vertices_m, o.mesh.triangles);
        o.material.rho_kg_m3 = so.mass_kg / volume_m3;
      }
      o.base_frequency_hz = so.base_frequency_hz > 0
                                ? so.base_frequency_hz
                                : kernels::fem::lowest_free_mode(o.mesh.vertices_m, o.mesh.triangles, o.material.youngs_pa,
                                                                 o.material.poisson, o.material.rho_kg_m3)
                                      .frequency_hz;
      if (!(o.base_frequency_hz < h.proxy_above_hz)) {
        ++spec.scene_above_threshold;
        continue;
      }
      if (!add(std::move(o))) ++spec.scene_duplicates;
    }
  }
  if (spec.objects.empty())
    throw InputError(spec.scene_bodies > 0
                         ? fmt::format("objects.scene: none of its {} objects is given by a mesh with a lowest frequency "
                                       "below objects.proxy_above_hz = {} Hz ({} without a mesh): no object bank to build",
                                       spec.scene_bodies, h.proxy_above_hz, spec.scene_without_mesh)
                         : std::string("objects.meshes = [] and no objects.scene: an object bank needs at least one object"));
  if (spec.objects.size() > kMaxObjects)
    throw InputError(fmt::format("{} objects; an object bank holds at most {}", spec.objects.size(), kMaxObjects));
  return spec;
}

std::string object_sweep_toml(const io::Config& config, const ObjectSpec& spec) {
  std::string text = config.to_toml() + "\n# the objects as read:\n";
  for (const ObjectSource& o : spec.objects) {
    const auto& m = o.material;
    text += fmt::format("# {} from {}: rho_kg_m3 = {:.17g}, youngs_pa = {:.17g}, poisson = {:.17g}, rayleigh_alpha_1_s = "
                        "{:.17g}, rayleigh_beta_s = {:.17g}\n",
                        o.key(), o.mesh_path, m.rho_kg_m3, m.youngs_pa, m.poisson, m.damping->alpha_1_s, m.damping->beta_s);
  }
  return text;
}

std::vector<ObjectTask> object_tasks(const ObjectSpec& spec) {
  std::vector<ObjectTask> tasks;
  for (std::size_t i = 0; i < spec.objects.size(); ++i) tasks.push_back({i, spec.objects[i].key()});
  return tasks;
}

}  // namespace clatter::jobs
