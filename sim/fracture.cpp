#include "sim/fracture.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "kernels/fracture/impulses.hpp"
#include "kernels/fracture/pattern.hpp"
#include "kernels/fracture/quasistatic.hpp"
#include "kernels/mass_properties.hpp"

namespace clatter::sim {
namespace {

namespace kf = kernels::fracture;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// SplitMix64's finalizer: each fracture's pattern seed from the run's seed, the body and the step,
// so a rerun gives the same pieces and two bodies breaking at once do not share seeds.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

struct Breakables::Body {
  kf::TetMesh mesh;
  double volume_m3 = 0, smallest_tet_m3 = 0;
  model::Material material;
  double toughness_j_m2 = 0, strength_pa = 0;
  std::unique_ptr<kf::QuasistaticSolver> solver;  // from the first contact on
  double refused_energy_j = 0;  // the largest E_S whose pattern could not pay for two pieces
};

Breakables::Breakables(const FractureSettings& settings) : settings_(settings) {}
Breakables::~Breakables() = default;
void Breakables::remove(int id) { bodies_.erase(id); }

void Breakables::insert(int id, kf::TetMesh mesh, const model::Material& material) {
  auto b = std::make_unique<Body>();
  b->toughness_j_m2 = settings_.toughness_j_m2 > 0 ? settings_.toughness_j_m2 : material.fracture_energy_j_m2.value_or(0);
  b->strength_pa = settings_.strength_pa > 0 ? settings_.strength_pa : material.tensile_strength_pa.value_or(0);
  if (!(b->toughness_j_m2 > 0) || !(b->strength_pa > 0))
    throw InputError(fmt::format("material {}: a breakable body needs fracture_energy_j_m2 and tensile_strength_pa "
                                 "(configs/materials.toml), or fracture.toughness_j_m2 and fracture.strength_pa",
                                 material.name));
  b->smallest_tet_m3 = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const double v = kf::tet_volume_m3(mesh, static_cast<int>(t));
    b->volume_m3 += v;
    b->smallest_tet_m3 = std::min(b->smallest_tet_m3, v);
  }
  b->mesh = std::move(mesh);
  b->material = material;
  bodies_[id] = std::move(b);
}

std::optional<Fracture> Breakables::check(int id, const std::vector<ContactSample>& contacts, const BodyState& state,
                                          double dt_s, double t_s, double absorbed_j) {
  Body& b = *bodies_.at(id);
  // The stress is scaled to the absorbed energy, so a step that absorbs less than any one
  // tetrahedron stores at the strength cannot break the body: no solve (resting and sliding
  // pieces). The least energy density at a largest principal stress sigma is
  // (1 - 2 nu^2 / (1 - nu)) sigma^2 / (2 E), the other two principal stresses free.
  const double nu = b.material.poisson;
  if (absorbed_j < (1 - 2 * nu * nu / (1 - nu)) * b.strength_pa * b.strength_pa / (2 * b.material.youngs_pa) * b.smallest_tet_m3) {
    ++stats_.skipped;
    return std::nullopt;
  }
  std::vector<kf::NodalForce> forces;
  for (const ContactSample& c : contacts) {
    if (c.a != id && c.b != id) continue;
    // Into the body frame at the step's start, where the contact was found.
    const io::Pose& pose = c.a == id ? c.pose_a : c.pose_b;
    const Vec3 force = scale(c.impulse_n_s, (c.a == id ? 1 : -1) / dt_s);
    if (!b.solver) {
      const auto t0 = std::chrono::steady_clock::now();
      b.solver = std::make_unique<kf::QuasistaticSolver>(b.mesh, b.material.youngs_pa, b.material.poisson, b.material.rho_kg_m3);
      stats_.factorize_s += seconds_since(t0);
      ++stats_.factorizations;
      stats_.largest_dofs = std::max(stats_.largest_dofs, b.solver->dofs());
    }
    b.solver->add_surface_force(forces, rotate_inverse(pose.orientation_wxyz, sub(c.point_m, pose.position_m)),
                                rotate_inverse(pose.orientation_wxyz, force), settings_.contact_radius_m);
  }
  if (forces.empty()) return std::nullopt;
  auto t0 = std::chrono::steady_clock::now();
  kf::StressField field = b.solver->solve(forces);
  stats_.solve_s += seconds_since(t0);
  ++stats_.stress_solves;
  // J/dt is the force of a contact that lasts one step; the elastic energy a contact stores cannot
  // exceed the kinetic energy it takes, so a force whose E_S would is scaled down until it does
  // (stress scales with the force, energy with its square).
  if (field.strain_energy_j > std::max(absorbed_j, 0.0)) {
    const double s = std::sqrt(std::max(absorbed_j, 0.0) / field.strain_energy_j);
    for (auto& sigma : field.stress_pa)
      for (auto& row : sigma)
        for (double& x : row) x *= s;
    for (double& x : field.max_principal_pa) x *= s;
    for (double& x : field.energy_density_j_m3) x *= s * s;
    field.strain_energy_j *= s * s;
    ++stats_.energy_bounded;
  }
  double peak = 0;
  for (double s : field.max_principal_pa) peak = std::max(peak, s);
  if (peak < b.strength_pa || b.volume_m3 < settings_.min_volume_m3 || field.strain_energy_j <= b.refused_energy_j)
    return std::nullopt;

  t0 = std::chrono::steady_clock::now();
  kf::PatternSettings ps;
  ps.fracture_energy_j_m2 = b.toughness_j_m2;
  ps.eta = settings_.eta;
  ps.alpha = settings_.alpha;
  ps.min_piece_volume_m3 = settings_.min_piece_m3;
  ps.seed = mix(settings_.seed ^ mix(static_cast<std::uint64_t>(id) ^ mix(static_cast<std::uint64_t>(std::llround(t_s / dt_s)))));
  kf::FracturePattern pattern = kf::fracture_pattern(b.mesh, field.energy_density_j_m3, field.strain_energy_j, ps);
  stats_.pattern_s += seconds_since(t0);
  if (pattern.pieces.size() < 2) {
    b.refused_energy_j = field.strain_energy_j;
    ++stats_.refused;
    return std::nullopt;
  }
  ++stats_.fractures;

  // The pieces' motion before the impulses: the body's rigid motion, in its own frame.
  const auto& q = state.pose.orientation_wxyz;
  const Vec3 v_body = rotate_inverse(q, state.velocity_m_s), w_body = rotate_inverse(q, state.angular_velocity_rad_s);
  std::vector<kf::PieceInertia> inertia;
  std::vector<Vec3> v, w;
  for (const kf::Piece& p : pattern.pieces) {
    const kernels::MeshMassProperties mp = kernels::mesh_mass_properties(p.mesh.nodes_m, p.surface);
    kf::PieceInertia i{b.material.rho_kg_m3 * mp.volume_m3, mp.centroid_m, {}};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) i.inertia_kg_m2[r][c] = b.material.rho_kg_m3 * mp.inertia_per_density_m5[r][c];
    inertia.push_back(i);
    v.push_back(add(v_body, cross(w_body, inertia.back().centre_m)));
    w.push_back(w_body);
  }
  const double released_j = field.strain_energy_j - pattern.fracture_energy_j;
  const kf::FractureImpulses impulses =
      kf::fracture_impulses(pattern.fracture_triangles, field.stress_pa, inertia, v, w, settings_.impulses ? released_j : 0);

  Fracture f;
  for (std::size_t d = 0; d < pattern.pieces.size(); ++d) {
    kf::Piece& p = pattern.pieces[d];
    NewPiece n;
    std::vector<int> index(p.mesh.nodes_m.size(), -1);  // the surface's own vertices, without the interior nodes
    for (const auto& t : p.surface) {
      std::array<int, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        int& i = index[t[k]];
        if (i < 0) i = static_cast<int>(n.surface_vertices_m.size()), n.surface_vertices_m.push_back(p.mesh.nodes_m[t[k]]);
        tri[k] = i;
      }
      n.surface_triangles.push_back(tri);
    }
    n.mesh = std::move(p.mesh);
    n.velocity_m_s = rotate(q, add(v[d], impulses.dv_m_s[d]));
    n.angular_velocity_rad_s = rotate(q, add(w[d], impulses.dw_rad_s[d]));
    f.pieces.push_back(std::move(n));
  }
  if (impulses.tau_s > 0)  // else nothing pushes the pieces: no fracture events
    for (const kf::InterfaceImpulse& i : impulses.interfaces)
      f.impulses.push_back({i.piece, add(state.pose.position_m, rotate(q, i.point_m)), rotate(q, i.impulse_n_s)});
  io::SceneFracture& r = f.record;
  r.t_s = t_s;
  r.body = id;
  r.max_principal_pa = peak;
  r.strength_pa = b.strength_pa;
  r.toughness_j_m2 = b.toughness_j_m2;
  r.strain_energy_j = field.strain_energy_j;
  r.fracture_area_m2 = pattern.area_m2;
  r.fracture_energy_j = pattern.fracture_energy_j;
  r.kinetic_energy_gained_j = impulses.kinetic_energy_gained_j;
  r.tau_s = impulses.tau_s;
  r.tets = b.mesh.tets.size();
  return f;
}

}  // namespace clatter::sim
