#pragma once
// The rigid-body world of clatter-sim: Bullet (double precision) behind a small interface that
// knows bodies by their scene ids. Fixed time step; convex hulls for collision; the ground is the
// plane z = 0; after each step, every contact point's applied impulse is reported. The only file
// that includes Bullet.
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "core/vec3.hpp"
#include "io/scene.hpp"

namespace clatter::sim {

struct WorldOptions {
  double dt_s = 2e-4;
  double gravity_m_s2 = 9.81;     // along -z
  int solver_iterations = 50;     // sequential-impulse sweeps per step
  double ground_friction = 0.6;   // combined with a body's as the product (Bullet's rule)
  double ground_restitution = 0.3;
};

struct BodyState {
  io::Pose pose;                        // centre of mass, body (principal) frame -> world
  Vec3 velocity_m_s{}, angular_velocity_rad_s{};  // world frame
};

struct BodySpec {
  int id = 0;                           // >= 1; 0 is the ground
  double mass_kg = 0;
  Vec3 principal_moments_kg_m2{};       // the body frame is the principal frame, centred on the centre of mass
  std::vector<Vec3> hull_m;             // points in the body frame; collision uses their convex hull
  double margin_m = 1e-3;               // Bullet's collision margin: the hull is shrunk by it first, so
  double gap_m = 0;                     // the rounded surface is the hull's, less gap_m (pre-fractured
                                        // pieces that touch are made not to overlap)
  double friction = 0.6, restitution = 0.3;
  // > 0: a hull of more vertices is replaced by Bullet's simplified one (its support points in 42
  // directions), slightly inside the exact hull; fracture pieces, whose fine surfaces make GJK slow.
  int max_hull_vertices = 0;
  BodyState initial;
};

// One contact point's share of one step.
struct ContactSample {
  int a = 0, b = 0;                     // scene ids; b = 0: the ground
  Vec3 point_m{};                       // world, at the step's start
  Vec3 impulse_n_s{};                   // on a (normal and both friction directions); b gets its opposite
  Vec3 normal{};                        // unit, from b towards a
  double approach_speed_m_s = 0;        // -(v_a - v_b) . normal at the point, from the step's starting velocities
  // When in the step the surfaces meet: Bullet's contacts are speculative (a point is solved while
  // still a gap d apart, so that it closes within the step), so contact begins d / approach speed
  // after the step's start (0 for points already touching).
  double touch_after_s = 0;
  io::Pose pose_a, pose_b;              // at the step's start
};

// The convex hull of `points` as a closed outward triangle mesh, simplified (Bullet's support
// points in 42 directions) when it has more than max_vertices vertices: the small solid whose
// lowest mode stands in for a fracture piece's (docs/fracture.md "Pieces' base frequency").
io::TriangleMesh convex_hull(const std::vector<Vec3>& points, int max_vertices = 64);

class World {
 public:
  explicit World(const WorldOptions& options);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  void add_body(const BodySpec& spec);
  void remove_body(int id);
  // The pieces of one fracture start interlocked (a piece that is not convex overlaps its
  // neighbours' hulls), so a pair given here does not collide until their bounding boxes part.
  void ignore_until_apart(int a, int b);
  bool has_body(int id) const { return bodies_.count(id) != 0; }
  BodyState state(int id) const;
  BodyState start_state(int id) const;  // at the last step's start
  std::size_t bodies() const { return bodies_.size(); }

  // One step of dt_s; afterwards contacts() holds the step's points with a non-zero impulse, in
  // Bullet's manifold order (deterministic for the same inputs).
  void step();
  double time_s() const { return static_cast<double>(steps_) * dt_s_; }
  const std::vector<ContactSample>& contacts() const { return contacts_; }

 private:
  struct Impl;
  struct Body;
  std::unique_ptr<Impl> impl_;
  std::map<int, std::unique_ptr<Body>> bodies_;
  std::set<std::pair<int, int>> ignored_;  // pairs that do not collide yet (a < b)
  std::vector<ContactSample> contacts_;
  std::size_t steps_ = 0;
  double dt_s_ = 0;
};

}  // namespace clatter::sim
