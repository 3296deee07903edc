#include "io/scene.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "io/text_file.hpp"
#include "io/text_number.hpp"

namespace clatter::io {
namespace {

using nlohmann::json;

[[noreturn]] void bad(const std::string& where, const std::string& what) { throw InputError(where + ": " + what); }

const json& need(const json& j, const std::string& key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) bad(where, "missing key '" + key + "'");
  return j.at(key);
}

// A list (objects, events): anything else is refused by name instead of indexed into.
const json& need_array(const json& j, const std::string& key, const std::string& where) {
  const json& a = need(j, key, where);
  if (!a.is_array()) bad(where + ": " + key, std::string("expected an array, found ") + a.type_name());
  return a;
}

// An object id >= 1 that fits an int: a larger one would wrap around into another object's id.
std::optional<int> object_id(const json& j) {
  if (!j.is_number_integer()) return std::nullopt;
  const auto v = j.get<std::int64_t>();
  if (v < 1 || v > std::numeric_limits<int>::max()) return std::nullopt;
  return static_cast<int>(v);
}

double number(const json& j, const std::string& where) {
  if (!j.is_number()) bad(where, "expected a number, found " + j.dump());
  const double v = j.get<double>();
  if (!std::isfinite(v)) bad(where, "not finite");
  return v;
}

template <std::size_t N>
std::array<double, N> vec(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != N) bad(where, fmt::format("expected an array of {} numbers, found {}", N, j.dump()));
  std::array<double, N> v{};
  for (std::size_t i = 0; i < N; ++i) v[i] = number(j[i], fmt::format("{}[{}]", where, i));
  return v;
}

// The norm of an orientation quaternion, refused (naming `where`) unless it is 1 within what text
// formats printing 5-6 digits leave. Rotations are not renormalized here: a JSON pose is used as
// given (off by at most 1e-4 in scale), and the James-lab reader divides by the norm as it inverts.
double unit_quaternion_norm(const std::array<double, 4>& q, const std::string& where, const std::string& shown) {
  constexpr double kTolerance = 1e-4;
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(std::abs(n - 1) <= kTolerance))
    bad(where, fmt::format("{} has norm {}: must be a unit quaternion (within {})", shown, n, kTolerance));
  return n;
}

// The optional Rayleigh pair of a material: both keys or neither.
// A material's number (its JSON value and "FILE: materials.NAME.KEY"), checked by the one rule of
// its table key (model::material_rule).
double material_number(const json& v, const std::string& where, const char* table_key) {
  const double x = number(v, where);
  if (const char* rule = model::material_rule(table_key, x)) bad(where, fmt::format("{}: {}", x, rule));
  return x;
}

// One named material of a scene: E and nu required, the Rayleigh pair (both or neither) and the
// density optional.
model::Material scene_material(const std::string& name, const json& m, const std::string& w) {
  model::Material mat;
  mat.name = name;
  mat.youngs_pa = material_number(need(m, "youngs_modulus_pa", w), w + ".youngs_modulus_pa", "youngs_pa");
  mat.poisson = material_number(need(m, "poisson_ratio", w), w + ".poisson_ratio", "poisson");
  const bool alpha = m.contains("rayleigh_alpha_1_s"), beta = m.contains("rayleigh_beta_s");
  if (alpha != beta) bad(w, "give both rayleigh_alpha_1_s and rayleigh_beta_s, or neither");
  if (alpha)
    mat.damping = model::RayleighDamping{material_number(m["rayleigh_alpha_1_s"], w + ".rayleigh_alpha_1_s", "rayleigh_alpha_1_s"),
                                         material_number(m["rayleigh_beta_s"], w + ".rayleigh_beta_s", "rayleigh_beta_s")};
  if (m.contains("density_kg_m3")) mat.rho_kg_m3 = material_number(m["density_kg_m3"], w + ".density_kg_m3", "rho_kg_m3");
  return mat;
}

Pose pose(const json& j, const std::string& where) {
  Pose p;
  p.position_m = vec<3>(need(j, "position_m", where), where + ".position_m");
  p.orientation_wxyz = vec<4>(need(j, "orientation_wxyz", where), where + ".orientation_wxyz");
  unit_quaternion_norm(p.orientation_wxyz, where + ".orientation_wxyz", json(p.orientation_wxyz).dump());
  return p;
}

// An object given by its shape: the mesh path (relative to the scene) and its density or mass;
// synth::load_scene reads the mesh and computes the mass properties.
void mesh_object(SceneObject& obj, const json& o, const std::string& w, const std::string& scene_path) {
  for (const char* key : {"volume_m3", "inertia_kg_m2"})
    if (o.contains(key)) bad(w + "." + key, "give either a mesh or volume_m3 and inertia_kg_m2, not both");
  const json& m = o["mesh"];
  if (!m.is_string() || m.get<std::string>().empty()) bad(w + ".mesh", m.dump() + ": expected the path of an OBJ file");
  std::filesystem::path file = m.get<std::string>();
  if (file.is_relative()) file = std::filesystem::path(scene_path).parent_path() / file;
  obj.mesh_path = file.string();
  if (o.contains("mass_kg") == o.contains("density_kg_m3")) bad(w, "an object with a mesh needs exactly one of mass_kg and density_kg_m3");
  const std::string key = o.contains("mass_kg") ? "mass_kg" : "density_kg_m3";
  const double given = number(o[key], w + "." + key);
  if (!(given > 0)) bad(w + "." + key, fmt::format("{}: must be > 0", given));
  (key == "mass_kg" ? obj.mass_kg : obj.density_kg_m3) = given;
}

// Everything but the events (shared by both input formats).
Scene read_setting(const json& root, const std::string& path) {
  Scene scene;
  scene.path = path;
  if (need(root, "format", path) != "clatter-scene")
    bad(path + ": format", fmt::format("{}, expected \"clatter-scene\"", root["format"].dump()));
  if (need(root, "format_version", path) != 1)
    bad(path + ": format_version", root["format_version"].dump() + ", this build reads version 1");
  const json& materials = need(root, "materials", path);
  if (!materials.is_object()) bad(path + ": materials", std::string("expected an object of named materials, found ") + materials.type_name());
  for (const auto& [name, m] : materials.items()) {
    scene.materials[name] = scene_material(name, m, path + ": materials." + name);
  }
  const json& g = need(root, "ground_material", path);
  if (!g.is_string() || !scene.materials.count(g.get<std::string>())) bad(path + ": ground_material", g.dump() + " is not in materials");
  scene.ground_material = g.get<std::string>();
  std::set<int> ids;
  const json& objects = need_array(root, "objects", path);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const std::string w = fmt::format("{}: objects[{}]", path, i);
    const json& o = objects[i];
    SceneObject obj;
    const json& id = need(o, "id", w);
    const auto checked_id = object_id(id);
    if (!checked_id) bad(w + ".id", fmt::format("{}: must be an integer in [1, {}] (0 is the ground)", id.dump(), std::numeric_limits<int>::max()));
    obj.id = *checked_id;
    if (!ids.insert(obj.id).second) bad(w + ".id", fmt::format("{} is used twice", obj.id));
    obj.where = w;
    if (o.contains("mesh"))
      mesh_object(obj, o, w, path);
    else {
      obj.mass_kg = number(need(o, "mass_kg", w), w + ".mass_kg");
      if (!(obj.mass_kg > 0)) bad(w + ".mass_kg", fmt::format("{}: must be > 0", obj.mass_kg));
      obj.volume_m3 = number(need(o, "volume_m3", w), w + ".volume_m3");
      if (!(obj.volume_m3 > 0)) bad(w + ".volume_m3", fmt::format("{}: must be > 0", obj.volume_m3));
      const json& inertia = need(o, "inertia_kg_m2", w);
      if (!inertia.is_array() || inertia.size() != 3) bad(w + ".inertia_kg_m2", "expected a 3x3 array");
      for (std::size_t r = 0; r < 3; ++r) obj.inertia_kg_m2[r] = vec<3>(inertia[r], fmt::format("{}.inertia_kg_m2[{}]", w, r));
    }
    const json& mat = need(o, "material", w);
    if (!mat.is_string() || !scene.materials.count(mat.get<std::string>())) bad(w + ".material", mat.dump() + " is not in materials");
    obj.material = mat.get<std::string>();
    if (o.contains("created_s")) obj.created_s = number(o["created_s"], w + ".created_s");
    if (o.contains("destroyed_s") && !o["destroyed_s"].is_null()) obj.destroyed_s = number(o["destroyed_s"], w + ".destroyed_s");
    if (!(obj.destroyed_s > obj.created_s)) bad(w + ".destroyed_s", fmt::format("{}: must be after created_s = {}", obj.destroyed_s, obj.created_s));
    if (o.contains("base_frequency_hz")) {
      obj.base_frequency_hz = number(o["base_frequency_hz"], w + ".base_frequency_hz");
      if (!(obj.base_frequency_hz > 0)) bad(w + ".base_frequency_hz", fmt::format("{}: must be > 0", obj.base_frequency_hz));
      obj.base_frequency_from = "scene";
    }
    scene.objects.push_back(obj);
  }
  const json& listeners = need(root, "listeners", path);
  if (!listeners.is_array() || listeners.empty()) bad(path + ": listeners", "expected at least one listener");
  for (std::size_t i = 0; i < listeners.size(); ++i) {
    const std::string w = fmt::format("{}: listeners[{}]", path, i);
    scene.listeners_m.push_back(vec<3>(need(listeners[i], "position_m", w), w + ".position_m"));
  }
  if (root.contains("duration_s")) {
    scene.duration_s = number(root["duration_s"], path + ": duration_s");
    if (!(scene.duration_s > 0)) bad(path + ": duration_s", fmt::format("{}: must be > 0", scene.duration_s));
  }
  return scene;
}

json parse(const std::string& text, const std::string& path) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {  // out_of_range too: a number beyond double's range
    throw InputError(fmt::format("{}: not valid JSON: {}", path, e.what()));
  }
}

// Object id -> its index in scene.objects, built once per file: scenes have ~1e3 objects and
// ~1e5 events, and each event looks its objects up.
using ObjectIndex = std::map<int, std::size_t>;
ObjectIndex index_objects(const Scene& scene) {
  ObjectIndex index;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) index[scene.objects[i].id] = i;
  return index;
}

// Checks one event against the scene's objects and the previous event (events must come in time
// order: a simulator that emits them otherwise has a bug worth hearing about).
void check_event(const ObjectIndex& objects, const SceneEvent& e, double previous_t) {
  if (!(e.t_s >= 0)) bad(e.where, fmt::format("time {} s: must be >= 0", e.t_s));
  if (e.t_s < previous_t)
    bad(e.where, fmt::format("time {} s is before the previous event's {} s: events must be in time order", e.t_s, previous_t));
  if (!objects.count(e.a)) bad(e.where, fmt::format("object {} is not in the scene's objects", e.a));
  if (e.b != 0 && !objects.count(e.b)) bad(e.where, fmt::format("object {} is not in the scene's objects", e.b));
  if (e.b == e.a) bad(e.where, fmt::format("object {} collides with itself", e.a));
  if (e.fracture || e.sustained) {
    if (!(e.contact_time_s > 0)) bad(e.where, fmt::format("contact_time_s {} s: must be > 0", e.contact_time_s));
  } else if (!(e.normal_speed_m_s > 0)) {
    bad(e.where, fmt::format("normal speed {} m/s: must be > 0", e.normal_speed_m_s));
  }
}

}  // namespace

Scene read_scene(const std::string& path, bool read_events) {
  return parse_scene(read_text_file(path, "the scene file"), path, read_events);
}

Scene parse_scene(const std::string& text, const std::string& path, bool read_events) {
  const json root = parse(text, path);
  Scene scene = read_setting(root, path);
  if (!read_events) return scene;
  const ObjectIndex objects = index_objects(scene);
  const json& events = need_array(root, "events", path);
  double previous = 0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const json& j = events[i];
    SceneEvent e;
    e.where = fmt::format("{}: events[{}]", path, i);
    e.t_s = number(need(j, "t_s", e.where), e.where + ".t_s");
    const json& a = need(j, "a", e.where);
    if (!object_id(a)) bad(e.where + ".a", a.dump() + ": expected an object id");
    e.a = *object_id(a);
    const json& b = need(j, "b", e.where);
    if (b == "ground" || b == "fracture")
      e.b = 0, e.fracture = b == "fracture";
    else if (object_id(b))
      e.b = *object_id(b);
    else
      bad(e.where + ".b", b.dump() + ": expected an object id, \"ground\" or \"fracture\"");
    e.point_m = vec<3>(need(j, "point_m", e.where), e.where + ".point_m");
    e.impulse_n_s = vec<3>(need(j, "impulse_n_s", e.where), e.where + ".impulse_n_s");
    // A contact gives its approach speed (Hertz) or, sustained, the time its force lasted.
    if (!e.fracture && j.contains("contact_time_s") == j.contains("normal_speed_m_s"))
      bad(e.where, "a contact event needs exactly one of normal_speed_m_s and contact_time_s");
    e.sustained = !e.fracture && j.contains("contact_time_s");
    if (e.fracture || e.sustained)
      e.contact_time_s = number(need(j, "contact_time_s", e.where), e.where + ".contact_time_s");
    else
      e.normal_speed_m_s = number(need(j, "normal_speed_m_s", e.where), e.where + ".normal_speed_m_s");
    e.pose_a = pose(need(j, "pose_a", e.where), e.where + ".pose_a");
    if (e.b != 0) e.pose_b = pose(need(j, "pose_b", e.where), e.where + ".pose_b");
    check_event(objects, e, previous);
    previous = e.t_s;
    scene.events.push_back(e);
  }
  return scene;
}

void read_impulse_events(const std::string& impulse_path, Scene& scene) {
  std::ifstream in(impulse_path);
  if (!in) throw InputError(impulse_path + ": cannot open the impulse file");
  const ObjectIndex objects = index_objects(scene);
  std::string line;
  double previous = scene.events.empty() ? 0 : scene.events.back().t_s;
  for (int number_of_line = 1; std::getline(in, line); ++number_of_line) {
    std::istringstream s(line);
    std::string kind;
    if (!(s >> kind) || kind[0] == '#') continue;
    SceneEvent e;
    e.where = fmt::format("{}:{}", impulse_path, number_of_line);
    auto next = [&](const char* what) {
      std::string token;
      if (!(s >> token)) bad(e.where, std::string("missing ") + what);
      return finite_number(token, what, e.where);
    };
    auto next_id = [&](const char* what) {
      const double v = next(what);
      if (v != std::floor(v) || v < 1 || v > std::numeric_limits<int>::max())
        bad(e.where, fmt::format("{} {}: expected an object id in [1, {}]", what, v, std::numeric_limits<int>::max()));
      return static_cast<int>(v);
    };
    // One body: contact point p in the rest pose, centre x at time t, inverse rotation q (w x y z,
    // world -> rest): the world contact point is R(q)^-1 p + x, and the body -> world rotation is q^-1.
    auto body = [&](int& id, Pose& pose, std::array<double, 3>& rest_point) {
      std::array<double, 4> q{};
      id = next_id("object id");
      for (auto* v : {&rest_point[0], &rest_point[1], &rest_point[2]}) *v = next("contact point p");
      for (auto* v : {&pose.position_m[0], &pose.position_m[1], &pose.position_m[2]}) *v = next("centre of mass x");
      for (auto* v : {&q[0], &q[1], &q[2], &q[3]}) *v = next("quaternion q");
      const double n = unit_quaternion_norm(q, e.where, fmt::format("object {}: quaternion", id));
      pose.orientation_wxyz = {q[0] / n, -q[1] / n, -q[2] / n, -q[3] / n};  // the inverse of q
    };
    std::array<double, 3> rest_a{}, rest_b{}, dir{};
    double j = 0;
    if (kind == "C" || kind == "P") {
      e.t_s = next("time t");
      body(e.a, e.pose_a, rest_a);
      if (kind == "P") body(e.b, e.pose_b, rest_b);
      e.normal_speed_m_s = next("normal speed vn");
      j = next("impulse J");
      for (auto* v : {&dir[0], &dir[1], &dir[2]}) *v = next("direction n");
      if (std::string extra; s >> extra) bad(e.where, "unexpected '" + extra + "' after the direction n");
    } else {
      bad(e.where, "'" + kind + "': expected C (object-ground) or P (object pair)");
    }
    check_event(objects, e, previous);
    // World contact point from A's rest-pose point, taken about A's centre of mass.
    const Vec3& c = scene.objects[objects.at(e.a)].rest_centre_m;
    const Vec3 turned = rotate(e.pose_a.orientation_wxyz, Vec3{rest_a[0] - c[0], rest_a[1] - c[1], rest_a[2] - c[2]});
    for (std::size_t k = 0; k < 3; ++k) {
      e.point_m[k] = turned[k] + e.pose_a.position_m[k];
      e.impulse_n_s[k] = j * dir[k];
    }
    previous = e.t_s;
    scene.events.push_back(e);
  }
}

}  // namespace clatter::io
