#pragma once
// Brittle fracture as 003 section 3 simulates it, for clatter-sim: every breakable body keeps its
// linear tetrahedral mesh (in its body frame) and, from its first contact on, its factorized
// quasistatic solver (kernels/fracture/quasistatic.hpp). Each step's contact forces give the
// stress; where the largest principal stress passes the tensile strength (Rankine), the body's
// energy-bounded fracture pattern (pattern.hpp) is cut and the fracture impulses (impulses.hpp)
// set the pieces moving. The pieces are breakable in turn.
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "io/scene.hpp"
#include "kernels/fracture/tet_mesh.hpp"
#include "model/material.hpp"
#include "sim/world.hpp"

namespace clatter::kernels::fracture {
class QuasistaticSolver;
}

namespace clatter::sim {

struct FractureSettings {
  double edge_m = 5e-3;             // tetrahedra of the stress mesh
  double contact_radius_m = 3e-3;   // a contact force spreads over the surface nodes this close
  double eta = 0.8, alpha = 0.15;   // 003 section 3.2
  bool impulses = true;             // 003 section 3.3 (off: Fig. 5's comparison)
  double toughness_j_m2 = 0;        // > 0: instead of the material's G_c
  double strength_pa = 0;           // > 0: instead of the material's tensile strength
  double min_volume_m3 = 2e-6;      // smaller pieces no longer break
  double min_piece_m3 = 2e-7;       // no fracture makes a piece smaller than this
  std::uint64_t seed = 1;
};

// A piece a fracture made, in the broken body's frame: its closed surface and tetrahedra, and its
// motion once the fracture impulses have acted (world frame).
struct NewPiece {
  std::vector<Vec3> surface_vertices_m;
  std::vector<std::array<int, 3>> surface_triangles;
  kernels::fracture::TetMesh mesh;
  Vec3 velocity_m_s{}, angular_velocity_rad_s{};
};

// A fracture impulse on one piece across one interface, world frame (piece: index into pieces).
struct NewImpulse {
  int piece = 0;
  Vec3 point_m{}, impulse_n_s{};
};

struct Fracture {
  std::vector<NewPiece> pieces;
  std::vector<NewImpulse> impulses;
  io::SceneFracture record;  // pieces' ids filled in by the caller
};

struct FractureStats {
  std::size_t factorizations = 0, stress_solves = 0, fractures = 0, refused = 0, energy_bounded = 0;
  std::size_t skipped = 0;  // contact steps that absorbed too little energy to break anything: no solve
  double factorize_s = 0, solve_s = 0, pattern_s = 0;
  std::size_t largest_dofs = 0;
};

class Breakables {
 public:
  explicit Breakables(const FractureSettings& settings);
  ~Breakables();

  // `mesh` in the body frame (principal, centred on the centre of mass); material with E, nu, rho,
  // G_c and tensile strength (or the settings' overrides). InputError when neither gives them.
  void insert(int id, kernels::fracture::TetMesh mesh, const model::Material& material);
  bool breakable(int id) const { return bodies_.count(id) != 0; }
  void remove(int id);

  // The step's contact samples on body `id` (state: its pose and velocities at the step's end; the
  // samples carry the pose at its start) -> a fracture, or nothing. dt_s turns impulses into
  // forces; absorbed_j is the kinetic energy the step's contacts took from the body, which bounds
  // the strain energy they can store (the forces are scaled down to it when J/dt asks for more).
  std::optional<Fracture> check(int id, const std::vector<ContactSample>& contacts, const BodyState& state, double dt_s,
                                double t_s, double absorbed_j);

  const FractureStats& stats() const { return stats_; }

 private:
  struct Body;
  FractureSettings settings_;
  std::map<int, std::unique_ptr<Body>> bodies_;
  FractureStats stats_;
};

}  // namespace clatter::sim
