#include "sim/simulate.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <optional>
#include <set>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "core/stage_log.hpp"
#include "io/materials.hpp"
#include "io/mesh.hpp"
#include "kernels/fem/lowest_mode.hpp"
#include "kernels/mass_properties.hpp"
#include "kernels/rigid_body.hpp"
#include "kernels/fracture/tet_mesh.hpp"
#include "sim/fracture.hpp"
#include "sim/piece_frequency.hpp"
#include "sim/impacts.hpp"
#include "sim/rigid_transform.hpp"
#include "sim/voronoi.hpp"
#include "sim/world.hpp"

namespace clatter::sim {
namespace {

using io::RealList;
using io::StringList;

// A solid's mass properties, its principal frame (the body frame of Bullet and of the scene) and,
// when asked for, its lowest free-vibration frequency.
struct Solid {
  double mass_kg = 0, volume_m3 = 0, surface_area_m2 = 0;
  Vec3 moments_kg_m2{};
  RigidTransform principal;  // body (principal, centred) frame -> the coordinates the mesh was given in
  // The mesh in the body frame: its vertices are Bullet's hull points, and the scene's poses place
  // it, so the OBJ the scene names is the simulated geometry.
  std::shared_ptr<const io::TriangleMesh> body_mesh;
  double base_frequency_hz = 0;  // 0: not computed
};

// The uniform solid of `material` a closed mesh bounds. with_base_frequency: the simulator knows
// each piece's shape, so it gives clatter-synth the piece's own lowest frequency (FEM,
// kernels/fem/lowest_mode.hpp), to which the modal proxy is scaled (003 section 5.4).
Solid solid_of(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles, const model::Material& material,
               bool with_base_frequency, const std::string& what) {
  const kernels::MeshMassProperties mp = kernels::mesh_mass_properties(vertices, triangles);
  if (!(mp.volume_m3 > 0)) throw InputError(fmt::format("{}: encloses no volume ({} m^3)", what, mp.volume_m3));
  const double density = material.rho_kg_m3;
  Solid s;
  s.volume_m3 = mp.volume_m3;
  s.surface_area_m2 = mp.surface_area_m2;
  s.mass_kg = density * mp.volume_m3;
  kernels::Mat3 inertia{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) inertia[i][j] = density * mp.inertia_per_density_m5[i][j];
  const kernels::ProxyFit fit = kernels::fit_proxy(inertia, s.mass_kg, s.volume_m3);
  s.moments_kg_m2 = fit.moments_kg_m2;
  s.principal = {quaternion_from_columns(fit.axes), mp.centroid_m};
  const RigidTransform to_body = s.principal.inverse();
  io::TriangleMesh body;
  body.vertices_m.reserve(vertices.size());
  for (const Vec3& v : vertices) body.vertices_m.push_back(to_body.apply(v));
  body.triangles = triangles;
  s.body_mesh = std::make_shared<const io::TriangleMesh>(std::move(body));
  if (with_base_frequency) {
    Stage stage("base frequency (FEM)");
    s.base_frequency_hz =
        kernels::fem::lowest_free_mode(vertices, triangles, material.youngs_pa, material.poisson, material.rho_kg_m3).frequency_hz;
  }
  return s;
}

// The table's material as the scene gives it: the bodies' density is their mass over their volume,
// so only the ground's is written (the ground sound checks it against its bank's). The fracture data
// and the source stay in the table.
model::Material scene_material(const model::Material& m, bool with_density) {
  model::Material s = m;
  if (!with_density) s.rho_kg_m3 = 0;
  s.fracture_energy_j_m2.reset(), s.tensile_strength_pa.reset();
  s.source.clear();
  return s;
}

Vec3 point(const RealList& list, std::size_t i = 0) { return {list[3 * i], list[3 * i + 1], list[3 * i + 2]}; }

class Simulation {
 public:
  Simulation(const io::Config& c, const std::string& config_path) : c_(c), config_path_(config_path) {
    options_.dt_s = c.real("sim.dt_s");
    options_.gravity_m_s2 = c.real("sim.gravity_m_s2");
    options_.solver_iterations = static_cast<int>(c.integer("sim.solver_iterations"));
    options_.ground_friction = c.real("ground.friction");
    options_.ground_restitution = c.real("ground.restitution");
    const auto& table = io::builtin_materials();
    body_material_ = io::find_material(table, c.string("bodies.material"), "bodies.material");
    ground_material_ = io::find_material(table, c.string("ground.material"), "ground.material");
    scene_.materials[body_material_.name] = scene_material(body_material_, false);
    scene_.materials[ground_material_.name] = scene_material(ground_material_, true);
    scene_.ground_material = ground_material_.name;
    FractureSettings f;
    f.edge_m = c.real("fracture.edge_m");
    f.contact_radius_m = c.real("fracture.contact_radius_m");
    f.eta = c.real("fracture.eta");
    f.alpha = c.real("fracture.alpha");
    f.impulses = c.boolean("fracture.impulses");
    f.toughness_j_m2 = c.real("fracture.toughness_j_m2");
    f.strength_pa = c.real("fracture.strength_pa");
    f.min_volume_m3 = c.real("fracture.min_volume_m3");
    f.min_piece_m3 = c.real("fracture.min_piece_m3");
    f.seed = static_cast<std::uint64_t>(c.integer("sim.seed"));
    breakables_ = std::make_unique<Breakables>(f);
    for (const std::string& b : c.strings("sim.bodies"))
      if (b != "plate" && b != "pile" && b != "slab" && b != "ball")
        throw InputError(fmt::format("sim.bodies: \"{}\": expected any of \"plate\", \"slab\", \"ball\", \"pile\"", b));
    const RealList& listeners = c.reals("listeners.positions_m");
    if (listeners.empty()) throw InputError("listeners.positions_m: []: give at least one listener");
    for (std::size_t i = 0; i < listeners.size() / 3; ++i) scene_.listeners_m.push_back(point(listeners, i));
    scene_.duration_s = c.real("sim.duration_s");
  }

  FractureReport on_fracture_;

  io::Scene run(SimStats* stats, const Progress& progress) {
    const auto t0 = std::chrono::steady_clock::now();
    World world(options_);
    {
      Stage stage("bodies");
      add_meshes(world);
      if (has("plate")) add_plate(world);
      if (has("slab")) add_slab(world);
      if (has("ball")) add_ball(world);
      if (has("pile")) add_pile(world);
    }
    if (world.bodies() == 0) throw InputError("nothing to simulate: give meshes.files or sim.bodies");
    ImpactRecorder recorder(options_.dt_s, {c_.real("record.impact_window_s"), c_.real("record.sustain_window_s"),
                                            c_.real("record.quiet_s"), c_.real("record.min_speed_m_s"),
                                            c_.real("record.merge_distance_m")});
    const auto steps = static_cast<std::size_t>(std::llround(scene_.duration_s / options_.dt_s));
    SimStats s;
    Stage steps_stage("steps");
    auto last_report = std::chrono::steady_clock::now();
    for (std::size_t n = 0; n < steps; ++n) {
      {
        Stage stage("bullet");  // ~1e4 calls of ~1 ms: the stage's own cost is negligible
        world.step();
      }
      Stage stage("events and fracture");
      recorder.add_step(static_cast<double>(n) * options_.dt_s, world.contacts());
      s.contact_samples += world.contacts().size();
      if (plate_id_ && world.has_body(plate_id_)) maybe_fracture(world, recorder, static_cast<double>(n + 1) * options_.dt_s, s);
      break_bodies(world, recorder, static_cast<double>(n + 1) * options_.dt_s, s);
      // Every tenth of the run, and every 10 s of wall time when steps are slow (a shattering body).
      const auto now = std::chrono::steady_clock::now();
      if (progress && ((n + 1) % std::max<std::size_t>(1, steps / 10) == 0 || now - last_report > std::chrono::seconds(10))) {
        progress(n + 1, steps);
        last_report = now;
      }
    }
    scene_.events = recorder.finish();
    for (const auto& [id, o] : objects_) {
      scene_.objects.push_back(o);
      if (world.has_body(id)) s.final_states[id] = world.state(id);
    }
    s.steps = steps;
    s.impacts = recorder.impacts();
    s.sustained = recorder.sustained();
    s.fracture = breakables_->stats();
    if (!scene_.fractures.empty() && s.fracture_s < 0) s.fracture_s = scene_.fractures.front().t_s;
    s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (stats) *stats = s;
    return scene_;
  }

 private:
  // Adds a body whose mesh coordinates map to the world by `placement`, moving with v, w.
  void add_body(World& world, int id, const Solid& solid, const RigidTransform& placement, const Vec3& v, const Vec3& w,
                double created_s, double gap_m, const model::Material* material = nullptr, int max_hull_vertices = 0) {
    if (!material) material = &body_material_;
    BodySpec spec;
    spec.id = id;
    spec.mass_kg = solid.mass_kg;
    spec.principal_moments_kg_m2 = solid.moments_kg_m2;
    spec.hull_m = solid.body_mesh->vertices_m;
    spec.margin_m = c_.real("bodies.margin_m");
    spec.gap_m = gap_m;
    spec.friction = c_.real("bodies.friction");
    spec.restitution = c_.real("bodies.restitution");
    spec.max_hull_vertices = max_hull_vertices;
    const RigidTransform body = placement.compose(solid.principal);
    spec.initial.pose = {body.translation_m, body.rotation};
    spec.initial.velocity_m_s = v;
    spec.initial.angular_velocity_rad_s = w;
    world.add_body(spec);
    io::SceneObject o;
    o.id = id;
    o.mass_kg = solid.mass_kg;
    o.volume_m3 = solid.volume_m3;
    for (int i = 0; i < 3; ++i) o.inertia_kg_m2[i][i] = solid.moments_kg_m2[i];
    o.material = material->name;
    if (!scene_.materials.count(material->name)) scene_.materials[material->name] = scene_material(*material, false);
    o.created_s = created_s;
    o.base_frequency_hz = solid.base_frequency_hz;
    o.mesh = solid.body_mesh;
    o.surface_area_m2 = solid.surface_area_m2;
    objects_[id] = o;
  }

  Solid solid(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles, const std::string& what) const {
    return solid_of(vertices, triangles, body_material_, c_.boolean("bodies.base_frequency"), what);
  }

  bool has(const char* body) const {
    const StringList& b = c_.strings("sim.bodies");
    return std::find(b.begin(), b.end(), body) != b.end();
  }

  // A body that breaks by physics (003 section 3): its stress mesh in its body frame.
  void add_breakable(World& world, const Solid& solid, const RigidTransform& placement, const Vec3& v, const Vec3& w,
                     const std::string& what) {
    const int id = next_id_++;
    kernels::fracture::TetMesh mesh;
    {
      Stage stage("stress mesh");
      try {
        mesh = kernels::fracture::tetrahedralize(solid.body_mesh->vertices_m, solid.body_mesh->triangles, c_.real("fracture.edge_m"));
      } catch (const std::invalid_argument& e) {
        throw InputError(fmt::format("{}: cannot be meshed for its stress: {}", what, e.what()));
      }
    }
    add_body(world, id, solid, placement, v, w, 0, 0);
    breakables_->insert(id, std::move(mesh), body_material_);
  }

  // 003 section 3 at every step: each breakable body in contact gets its quasistatic stress; one
  // that breaks is replaced by its pieces, which carry the fracture impulses' velocities, and the
  // impulses become the scene's fracture events.
  void break_bodies(World& world, ImpactRecorder& recorder, double t_s, SimStats& s) {
    std::set<int> touched;
    for (const ContactSample& c : world.contacts()) {
      if (breakables_->breakable(c.a)) touched.insert(c.a);
      if (c.b && breakables_->breakable(c.b)) touched.insert(c.b);
    }
    for (int id : touched) {
      if (!world.has_body(id)) continue;
      const BodyState state = world.state(id);
      std::optional<Fracture> f;
      {
        Stage stage("stress and fracture");
        f = breakables_->check(id, world.contacts(), state, options_.dt_s, t_s, absorbed_energy(world, id));
      }
      if (!f) continue;
      Stage stage("pieces");
      world.remove_body(id);
      breakables_->remove(id);
      objects_.at(id).destroyed_s = t_s;
      const RigidTransform placement{state.pose.orientation_wxyz, state.pose.position_m};
      std::vector<int> ids;
      for (std::size_t d = 0; d < f->pieces.size(); ++d) {
        NewPiece& p = f->pieces[d];
        Solid piece = solid_of(p.surface_vertices_m, p.surface_triangles, body_material_, false, fmt::format("piece {} of body {}", d, id));
        if (c_.boolean("bodies.base_frequency")) {
          Stage hull_stage("base frequency (FEM of the hull)");
          // In the body (principal) frame, where the piece's thinnest extent is its thickness.
          piece.base_frequency_hz = piece_base_frequency_hz(piece.body_mesh->vertices_m, piece.volume_m3, body_material_);
        }
        const int pid = next_id_++;
        add_body(world, pid, piece, placement, p.velocity_m_s, p.angular_velocity_rad_s, t_s, 0, nullptr, 64);
        // The piece's stress mesh in its own body frame.
        const RigidTransform to_body = piece.principal.inverse();
        for (Vec3& x : p.mesh.nodes_m) x = to_body.apply(x);
        breakables_->insert(pid, std::move(p.mesh), body_material_);
        for (int other : ids) world.ignore_until_apart(pid, other);
        ids.push_back(pid);
      }
      for (const NewImpulse& i : f->impulses) {
        io::SceneEvent e;
        e.t_s = t_s;
        e.a = ids[i.piece];
        e.fracture = true;
        e.contact_time_s = f->record.tau_s;
        e.point_m = i.point_m;
        e.impulse_n_s = i.impulse_n_s;
        e.pose_a = world.state(e.a).pose;
        recorder.add_event(e);
        ++s.fracture_events;
      }
      f->record.pieces = ids;
      scene_.fractures.push_back(f->record);
      if (on_fracture_) on_fracture_(f->record);
    }
  }

  // The kinetic energy the step's contacts took from body id and the bodies it touched (a struck
  // pane at rest gains energy; its striker loses it): what the contacts could have stored.
  double absorbed_energy(const World& world, int id) const {
    std::set<int> bodies{id};
    for (const ContactSample& c : world.contacts())
      if (c.a == id || c.b == id) bodies.insert(c.a == id ? c.b : c.a);
    double lost = 0;
    for (int b : bodies)
      if (b && world.has_body(b)) lost += kinetic_energy(b, world.start_state(b)) - kinetic_energy(b, world.state(b));
    return lost;
  }

  double kinetic_energy(int id, const BodyState& b) const {
    const io::SceneObject& o = objects_.at(id);
    const Vec3 w = rotate_inverse(b.pose.orientation_wxyz, b.angular_velocity_rad_s);  // principal frame
    double e = o.mass_kg * dot(b.velocity_m_s, b.velocity_m_s);
    for (int i = 0; i < 3; ++i) e += o.inertia_kg_m2[i][i] * w[i] * w[i];
    return e / 2;
  }

  // A box of slab.size_m centred on its own origin, turned by slab.rotation_deg about x, then y.
  void add_slab(World& world) {
    const Vec3 size = vector3("slab.size_m");
    if (!(size[0] > 0 && size[1] > 0 && size[2] > 0))
      throw InputError(fmt::format("slab.size_m: [{}, {}, {}]: every size must be > 0", size[0], size[1], size[2]));
    const Piece box = voronoi_pieces(scale(size, -0.5), scale(size, 0.5), {}, {{0, 0, 0}}).front();
    const Vec3 turn = vector3("slab.rotation_deg");
    const double d = std::numbers::pi / 180;
    const Quaternion qx{std::cos(turn[0] * d / 2), std::sin(turn[0] * d / 2), 0, 0};
    const Quaternion qy{std::cos(turn[1] * d / 2), 0, std::sin(turn[1] * d / 2), 0};
    const Quaternion qz{std::cos(turn[2] * d / 2), 0, 0, std::sin(turn[2] * d / 2)};
    const RigidTransform placement{multiply(qz, multiply(qy, qx)), vector3("slab.position_m")};
    add_breakable(world, solid(box.vertices_m, box.triangles, "slab"), placement, vector3("slab.velocity_m_s"), {}, "slab");
  }

  // A ball that does not break (the windows' projectile), of its own material.
  void add_ball(World& world) {
    ball_material_ = io::find_material(io::builtin_materials(), c_.string("ball.material"), "ball.material");
    // A polyhedron of 64 faces tangent to the sphere at Fibonacci directions: voro++ cuts it.
    const double r = c_.real("ball.radius_m");
    std::vector<HalfSpace> faces;
    for (int k = 0; k < 64; ++k) {
      const double z = 1 - (2 * k + 1) / 64.0, a = k * std::numbers::pi * (3 - std::sqrt(5.0));
      faces.push_back({{std::sqrt(1 - z * z) * std::cos(a), std::sqrt(1 - z * z) * std::sin(a), z}, r});
    }
    const Piece sphere = voronoi_pieces({-2 * r, -2 * r, -2 * r}, {2 * r, 2 * r, 2 * r}, faces, {{0, 0, 0}}).front();
    add_body(world, next_id_++, solid_of(sphere.vertices_m, sphere.triangles, ball_material_, c_.boolean("bodies.base_frequency"), "ball"),
             {{1, 0, 0, 0}, vector3("ball.position_m")}, vector3("ball.velocity_m_s"), {}, 0, 0, &ball_material_);
  }

  void add_meshes(World& world) {
    const StringList& files = c_.strings("meshes.files");
    const RealList& at = c_.reals("meshes.positions_m");
    const RealList& v = c_.reals("meshes.velocities_m_s");
    if (at.size() != 3 * files.size())
      throw InputError(fmt::format("meshes.positions_m: {} points for {} meshes.files: give one per file", at.size() / 3, files.size()));
    if (!v.empty() && v.size() != at.size())
      throw InputError(fmt::format("meshes.velocities_m_s: {} velocities for {} meshes.files: give one per file, or none",
                                   v.size() / 3, files.size()));
    for (std::size_t i = 0; i < files.size(); ++i) {
      std::filesystem::path file = files[i];
      if (file.is_relative() && !config_path_.empty()) file = std::filesystem::path(config_path_).parent_path() / file;
      const io::TriangleMesh mesh = io::read_obj(file.string());
      add_body(world, next_id_++, solid(mesh.vertices_m, mesh.triangles, file.string()), {{1, 0, 0, 0}, point(at, i)}, v.empty() ? Vec3{} : point(v, i), {}, 0, 0);
    }
  }

  // The plate's outline: a regular polygon of `sides` around its circumradius, `thickness` thick,
  // centred on the origin of its own coordinates with its faces normal to z.
  void add_plate(World& world) {
    const auto pieces = static_cast<std::size_t>(c_.integer("plate.pieces"));
    const double r = c_.real("plate.radius_m"), t = c_.real("plate.thickness_m");
    const auto sides = static_cast<int>(c_.integer("plate.sides"));
    const double apothem = r * std::cos(std::numbers::pi / sides);
    std::vector<HalfSpace> planes;
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * std::numbers::pi * (k + 0.5) / sides;
      planes.push_back({{std::cos(a), std::sin(a), 0}, apothem});
    }
    const Vec3 lo{-r, -r, -t / 2}, hi{r, r, t / 2};
    // Seeds uniform over the disc inside the outline (in the mid-plane: the pieces are prisms
    // through the thickness, as a plate breaks).
    Uniform u(static_cast<std::uint64_t>(c_.integer("sim.seed")));
    std::vector<Vec3> seeds;
    while (seeds.size() < pieces) {
      const Vec3 p{(2 * u() - 1) * apothem, (2 * u() - 1) * apothem, 0};
      if (p[0] * p[0] + p[1] * p[1] < 0.95 * 0.95 * apothem * apothem) seeds.push_back(p);
    }
    const Piece whole = voronoi_pieces(lo, hi, planes, {{0, 0, 0}}).front();
    const double tilt = c_.real("plate.tilt_deg") * std::numbers::pi / 180;
    const RigidTransform placement{{std::cos(tilt / 2), std::sin(tilt / 2), 0, 0}, vector3("plate.position_m")};
    const Solid plate = solid(whole.vertices_m, whole.triangles, "plate");
    if (!pieces) {  // it breaks by physics
      add_breakable(world, plate, placement, vector3("plate.velocity_m_s"), {}, "plate");
      return;
    }
    {
      Stage stage("voronoi");
      plate_pieces_ = voronoi_pieces(lo, hi, planes, seeds);
    }
    plate_id_ = next_id_++;
    plate_principal_ = plate.principal;
    add_body(world, plate_id_, plate, placement, vector3("plate.velocity_m_s"), {}, 0, 0);
  }

  // At the plate's first contact that approaches faster than plate.break_speed_m_s: it is replaced by its pieces, each moving as the plate did at its place,
  // plus a push of plate.kick_m_s away from the impact point in the plate's plane (recorded as
  // fracture events; not yet 003 section 3.3's fracture impulse, which issue 30 brings). Until then
  // it bounces whole, and rings as the intact plate it is (a stand-in for 003 section 3.1's stress
  // criterion: a plate struck harder breaks).
  void maybe_fracture(World& world, ImpactRecorder& recorder, double t_s, SimStats& s) {
    Vec3 at{};
    double weight = 0, fastest_m_s = 0;
    for (const ContactSample& c : world.contacts())
      if (c.a == plate_id_ || c.b == plate_id_) {
        const double w = std::sqrt(dot(c.impulse_n_s, c.impulse_n_s));
        at = add(at, scale(c.point_m, w));
        weight += w;
        if (w > 0) fastest_m_s = std::max(fastest_m_s, c.approach_speed_m_s);
      }
    if (!(weight > 0) || fastest_m_s < c_.real("plate.break_speed_m_s")) return;
    at = scale(at, 1 / weight);
    const BodyState plate = world.state(plate_id_);
    world.remove_body(plate_id_);
    objects_.at(plate_id_).destroyed_s = t_s;
    s.fracture_s = t_s;
    // Plate coordinates -> world, now.
    const RigidTransform placement = RigidTransform{plate.pose.orientation_wxyz, plate.pose.position_m}.compose(plate_principal_.inverse());
    const Vec3 normal = rotate(placement.rotation, {0, 0, 1});
    const double kick = c_.real("plate.kick_m_s"), gap = c_.real("plate.gap_m");
    for (std::size_t i = 0; i < plate_pieces_.size(); ++i) {
      const Piece& p = plate_pieces_[i];
      const Solid piece = solid(p.vertices_m, p.triangles, fmt::format("plate piece {}", i));
      const Vec3 centre = placement.apply(piece.principal.translation_m);
      Vec3 away = sub(centre, at);
      away = sub(away, scale(normal, dot(away, normal)));
      const double len = std::sqrt(dot(away, away));
      const Vec3 push = len > 0 ? scale(away, kick / len) : Vec3{};
      const Vec3 v = add(add(plate.velocity_m_s, cross(plate.angular_velocity_rad_s, sub(centre, plate.pose.position_m))), push);
      const int id = next_id_++;
      add_body(world, id, piece, placement, v, plate.angular_velocity_rad_s, t_s, gap);
      if (len > 0 && kick > 0) {
        io::SceneEvent e;
        e.t_s = t_s;
        e.a = id;
        e.fracture = true;
        e.contact_time_s = c_.real("plate.fracture_time_s");
        e.point_m = placement.apply(p.fracture_centroid_m);
        e.impulse_n_s = scale(push, piece.mass_kg);
        e.pose_a = world.state(id).pose;
        recorder.add_event(e);
        ++s.fracture_events;
      }
    }
  }

  void add_pile(World& world) {
    const auto pieces = static_cast<std::size_t>(c_.integer("pile.pieces"));
    if (!pieces) return;
    const Vec3 size = vector3("pile.size_m"), centre = vector3("pile.position_m");
    if (!(size[0] > 0 && size[1] > 0 && size[2] > 0))
      throw InputError(fmt::format("pile.size_m: [{}, {}, {}]: every size must be > 0", size[0], size[1], size[2]));
    const Vec3 lo = sub(centre, scale(size, 0.5)), hi = add(centre, scale(size, 0.5));
    Uniform u(static_cast<std::uint64_t>(c_.integer("sim.seed")));
    std::vector<Vec3> seeds;
    for (std::size_t i = 0; i < pieces; ++i) seeds.push_back({lo[0] + u() * size[0], lo[1] + u() * size[1], lo[2] + u() * size[2]});
    const Vec3 v0 = vector3("pile.velocity_m_s");
    const double shear = c_.real("pile.shear_1_s"), gap = c_.real("pile.gap_m");
    std::vector<Piece> rocks;
    {
      Stage stage("voronoi");
      rocks = voronoi_pieces(lo, hi, {}, seeds);
    }
    std::size_t i = 0;
    for (const Piece& p : rocks) {
      const Solid rock = solid(p.vertices_m, p.triangles, fmt::format("pile piece {}", i++));
      // The block slides as a sheared layer: the higher a rock, the faster it moves along x.
      const double height = rock.principal.translation_m[2] - lo[2];
      add_body(world, next_id_++, rock, {}, add(v0, {shear * height, 0, 0}), {}, 0, gap);
    }
  }

  // A key that holds one vector: exactly 3 numbers.
  Vec3 vector3(const char* key) const {
    const RealList& v = c_.reals(key);
    if (v.size() != 3) throw InputError(fmt::format("{}: {} numbers: expected 3 (x, y, z)", key, v.size()));
    return {v[0], v[1], v[2]};
  }

  const io::Config& c_;
  std::string config_path_;
  WorldOptions options_;
  model::Material body_material_, ground_material_, ball_material_;
  std::unique_ptr<Breakables> breakables_;
  io::Scene scene_;
  std::map<int, io::SceneObject> objects_;  // every body the run created, by id
  int next_id_ = 1, plate_id_ = 0;
  std::vector<Piece> plate_pieces_;          // the plate's cells, in its own coordinates
  RigidTransform plate_principal_;           // the whole plate's principal frame in those coordinates
};

}  // namespace

const io::Schema& sim_schema() {
  using io::Range;
  static const io::Schema schema{
      "clatter-sim: a rigid-body simulation (Bullet) -> a native Clatter scene of contact and fracture impulses; "
      "the defaults drop a ceramic plate that shatters on concrete (scenes/plate.toml)",
      {
          {"sim.dt_s", 2e-4, "fixed rigid-body time step [s] (5 kHz: 003 uses 5-10 kHz for sound)", Range{0, 0.01, true}},
          {"sim.duration_s", 1.5, "simulated time, and the scene's duration [s]", Range{0, 600, true}},
          {"sim.gravity_m_s2", 9.81, "gravity, along -z [m/s^2]", Range{0, 1000}},
          {"sim.solver_iterations", std::int64_t{50}, "Bullet's sequential-impulse iterations per step", Range{1, 10000}},
          {"sim.seed", std::int64_t{1}, "seed of the Voronoi sites (plate and pile) and of the fracture patterns", Range{0, 9.0e15}},
          {"sim.bodies", io::StringList{"plate"}, "the built-in bodies in the scene: any of \"plate\", \"slab\", \"ball\", "
                                                  "\"pile\" (besides meshes.files)"},
          {"record.impact_window_s", 2e-3, "longest impact: a contact point's first event sums at most this much of its "
           "impulse (sim/impacts.hpp, docs/synth.md) [s]", Range{0, 10, true}},
          {"record.sustain_window_s", 0.1, "a point still pushing after its impact continues as sustained-contact events "
           "this long [s]", Range{0, 100, true}},
          {"record.quiet_s", 1e-3, "a point without impulse for longer than this ends its event [s]", Range{0, 10}},
          {"record.merge_distance_m", 0.01, "contact points of one pair closer than this are one event [m]", Range{0, 10}},
          {"record.min_speed_m_s", 0.05, "a first event approaching slower than this is a sustained contact, not an impact [m/s]",
           Range{0, 100}},
          {"bodies.material", std::string("ceramic"), "material of every body: a table of configs/materials.toml"},
          {"bodies.friction", 0.5, "Coulomb friction coefficient of the bodies (Bullet multiplies the pair's)", Range{0, 10}},
          {"bodies.restitution", 0.3, "restitution of the bodies (Bullet multiplies the pair's)", Range{0, 1}},
          {"bodies.base_frequency", true, "compute each body's lowest free-vibration frequency from its mesh (FEM) for "
           "the scene's base_frequency_hz"},
          {"bodies.margin_m", 1e-3, "Bullet's collision margin [m]: hulls are shrunk by it, so surfaces stay where they are",
           Range{0, 0.1}},
          {"ground.material", std::string("concrete"), "material of the ground plane z = 0: a table of configs/materials.toml"},
          {"ground.friction", 0.8, "friction coefficient of the ground", Range{0, 10}},
          {"ground.restitution", 0.5, "restitution of the ground", Range{0, 1}},
          {"meshes.files", io::StringList{}, "bodies from closed triangle meshes (OBJ, relative to the config; convex hulls collide)"},
          {"meshes.positions_m", io::RealList{}, "where each mesh's coordinate origin starts [m]", {}, {}, 3},
          {"meshes.velocities_m_s", io::RealList{}, "each mesh's starting velocity [m/s] (empty: at rest)", {}, {}, 3},
          {"plate.pieces", std::int64_t{0}, "0: the plate breaks by physics (003 section 3, fracture.*); N > 0: it is pre-fractured "
                                            "into N Voronoi pieces and breaks at its first contact faster than plate.break_speed_m_s "
                                            "(the fast option)", Range{0, 100000}},
          {"plate.radius_m", 0.13, "the plate's outer radius (polygon circumradius) [m]", Range{0, 100, true}},
          {"plate.thickness_m", 0.006, "its thickness [m]", Range{0, 100, true}},
          {"plate.sides", std::int64_t{32}, "sides of its polygonal outline", Range{3, 1000}},
          {"plate.position_m", io::RealList{0, 0, 0.5}, "its centre at the start [m]"},
          {"plate.tilt_deg", 40.0, "its tilt about the x axis at the start [deg]", Range{-90, 90}},
          {"plate.velocity_m_s", io::RealList{0, 0, 0}, "its starting velocity [m/s]"},
          {"plate.kick_m_s", 0.5, "speed each piece gets away from the impact point, in the plate's plane, as it breaks [m/s]",
           Range{0, 100}},
          {"plate.break_speed_m_s", 4.0, "the plate breaks at its first contact approaching faster than this (0: its first "
                                         "contact) [m/s]; it bounces whole before", Range{0, 1000}},
          {"plate.fracture_time_s", 2e-4, "duration of each fracture impulse (the scene's contact_time_s) [s]", Range{0, 1, true}},
          {"plate.gap_m", 2e-4, "pieces collide as if this much smaller on each side, so neighbours start apart [m]",
           Range{0, 0.01}},
          {"slab.size_m", io::RealList{0.2, 0.2, 0.015}, "a breakable box (003's glass slab, windows, tile) of this size along "
                                                        "its x, y, z [m]"},
          {"slab.position_m", io::RealList{0, 0, 1.0}, "its centre at the start [m]"},
          {"slab.rotation_deg", io::RealList{0, 0, 0}, "its turn at the start about x, then y, then z [deg]"},
          {"slab.velocity_m_s", io::RealList{0, 0, 0}, "its starting velocity [m/s]"},
          {"ball.material", std::string("steel"), "material of the ball (it does not break): a table of configs/materials.toml"},
          {"ball.radius_m", 0.02, "its radius [m] (a 64-face polyhedron around the sphere)", Range{0, 10, true}},
          {"ball.position_m", io::RealList{0, -0.3, 0.5}, "its centre at the start [m]"},
          {"ball.velocity_m_s", io::RealList{0, 10, 0}, "its starting velocity [m/s]"},
          {"fracture.edge_m", 5e-3, "edge length of the linear tetrahedra of a breakable body's stress mesh [m]", Range{0, 1, true}},
          {"fracture.contact_radius_m", 3e-3, "a contact force spreads over the surface nodes this close to its point [m]",
           Range{0, 1}},
          {"fracture.eta", 0.8, "share of the strain energy the fracture surfaces may consume: G_c A_F <= eta E_S (003 section 3.2)",
           Range{0, 1, true}},
          {"fracture.alpha", 0.15, "region weights (strain energy density at the seed)^alpha (003 section 3.2)", Range{0, 10}},
          {"fracture.impulses", true, "apply 003 section 3.3's fracture impulses (E_S - E_F as the pieces' kinetic energy, "
                                      "the scene's fracture events); false: pieces start with the body's motion (Fig. 5's inset)"},
          {"fracture.toughness_j_m2", 0.0, "G_c [J/m^2] instead of the material's fracture_energy_j_m2 (0: the material's)",
           Range{0, 1e9}},
          {"fracture.strength_pa", 0.0, "tensile strength [Pa] instead of the material's tensile_strength_pa (0: the material's)",
           Range{0, 1e12}},
          {"fracture.min_volume_m3", 2e-6, "pieces smaller than this no longer break [m^3]", Range{0, 1e9}},
          {"fracture.min_piece_m3", 2e-7, "a fracture pattern stops adding seeds before a piece would be smaller than this "
                                          "[m^3]: the stress mesh must resolve its pieces", Range{0, 1e9}},
          {"pile.pieces", std::int64_t{0}, "a block of loose Voronoi rocks of this many pieces (0: none)", Range{0, 100000}},
          {"pile.size_m", io::RealList{0.4, 0.3, 0.25}, "the block's size along x, y, z [m]"},
          {"pile.position_m", io::RealList{0, 0, 0.35}, "the block's centre at the start [m]"},
          {"pile.velocity_m_s", io::RealList{1.0, 0, 0}, "the block's starting velocity [m/s]"},
          {"pile.shear_1_s", 4.0, "extra x velocity per metre of height in the block, a sliding layer [1/s]", Range{-1000, 1000}},
          {"pile.gap_m", 2e-3, "rocks collide as if this much smaller on each side, so neighbours start apart [m]",
           Range{0, 0.1}},
          {"listeners.positions_m", io::RealList{0.0, 1.2, 0.6}, "listener positions of the scene [m]", {}, {}, 3},
      }};
  return schema;
}

io::Scene simulate(const io::Config& config, const std::string& config_path, SimStats* stats, const Progress& progress,
                   const FractureReport& on_fracture) {
  Simulation sim(config, config_path);
  sim.on_fracture_ = on_fracture;
  return sim.run(stats, progress);
}

}  // namespace clatter::sim
