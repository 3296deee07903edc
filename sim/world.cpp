#include "sim/world.hpp"

#include <btBulletDynamicsCommon.h>
#include <fmt/format.h>

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btShapeHull.h>
#include <LinearMath/btConvexHullComputer.h>
#include <algorithm>
#include <stdexcept>

namespace clatter::sim {
namespace {

btVector3 bt(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 vec(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

io::Pose pose_of(const btTransform& t) {
  const btQuaternion q = t.getRotation();
  return {vec(t.getOrigin()), {q.w(), q.x(), q.y(), q.z()}};
}

btTransform transform_of(const io::Pose& p) {
  const auto& q = p.orientation_wxyz;
  return btTransform(btQuaternion(q[1], q[2], q[3], q[0]), bt(p.position_m));
}

}  // namespace

io::TriangleMesh convex_hull(const std::vector<Vec3>& points, int max_vertices) {
  btConvexHullComputer hull;
  hull.compute(points.front().data(), static_cast<int>(sizeof(Vec3)), static_cast<int>(points.size()), 0, 0);
  if (hull.vertices.size() > max_vertices) {
    btConvexHullShape exact(&hull.vertices[0][0], hull.vertices.size(), static_cast<int>(sizeof(btVector3)));
    exact.setMargin(0);
    btShapeHull reduced(&exact);
    reduced.buildHull(0);
    std::vector<Vec3> kept;
    for (int i = 0; i < reduced.numVertices(); ++i) kept.push_back(vec(reduced.getVertexPointer()[i]));
    hull.compute(kept.front().data(), static_cast<int>(sizeof(Vec3)), static_cast<int>(kept.size()), 0, 0);
  }
  io::TriangleMesh out;
  for (int i = 0; i < hull.vertices.size(); ++i) out.vertices_m.push_back(vec(hull.vertices[i]));
  for (int f = 0; f < hull.faces.size(); ++f) {  // each face a convex polygon, counter-clockwise: a fan
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    const int apex = first->getSourceVertex();
    for (const btConvexHullComputer::Edge* e = first->getNextEdgeOfFace(); e->getTargetVertex() != apex; e = e->getNextEdgeOfFace())
      out.triangles.push_back({apex, e->getSourceVertex(), e->getTargetVertex()});
  }
  return out;
}

struct World::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  btStaticPlaneShape ground_shape{btVector3(0, 0, 1), 0};
  btDefaultMotionState ground_motion;
  std::unique_ptr<btRigidBody> ground;
  WorldOptions options;
};

struct World::Body {
  int id = 0;
  std::unique_ptr<btConvexHullShape> shape;
  std::unique_ptr<btDefaultMotionState> motion;
  std::unique_ptr<btRigidBody> body;
  btTransform start;  // at the current step's start
  btVector3 v_start, w_start;
};

World::World(const WorldOptions& options) : impl_(std::make_unique<Impl>()) {
  if (!(options.dt_s > 0)) throw std::invalid_argument("World: dt_s must be > 0");
  impl_->options = options;
  dt_s_ = options.dt_s;
  // Resting faces and edges on the plane get several points in one step, not one per step.
  impl_->configuration.setPlaneConvexMultipointIterations(3, 3);
  btDiscreteDynamicsWorld& w = impl_->world;
  w.setGravity(btVector3(0, 0, -options.gravity_m_s2));
  btContactSolverInfo& info = w.getSolverInfo();
  info.m_numIterations = options.solver_iterations;
  // Friction along two directions per point, so the recorded friction impulse is the one applied;
  // no random constraint order (determinism).
  info.m_solverMode = SOLVER_USE_WARMSTARTING | SOLVER_SIMD | SOLVER_USE_2_FRICTION_DIRECTIONS;
  btRigidBody::btRigidBodyConstructionInfo ground_info(0, &impl_->ground_motion, &impl_->ground_shape);
  ground_info.m_friction = options.ground_friction;
  ground_info.m_restitution = options.ground_restitution;
  impl_->ground = std::make_unique<btRigidBody>(ground_info);
  impl_->ground->setUserIndex(0);
  w.addRigidBody(impl_->ground.get());
}

World::~World() {
  for (auto& [id, b] : bodies_) impl_->world.removeRigidBody(b->body.get());
  impl_->world.removeRigidBody(impl_->ground.get());
}

void World::add_body(const BodySpec& s) {
  if (s.id < 1 || bodies_.count(s.id)) throw std::invalid_argument(fmt::format("World::add_body: id {} is not new and >= 1", s.id));
  if (!(s.mass_kg > 0) || s.hull_m.size() < 4) throw std::invalid_argument(fmt::format("World::add_body: body {} needs mass and 4+ hull points", s.id));
  auto b = std::make_unique<Body>();
  b->id = s.id;
  // The hull shrunk by margin + gap, then Bullet's margin put back around it: the collision surface
  // is the hull less the gap (corners rounded by the margin).
  btConvexHullComputer hull;
  const double shrunk = hull.compute(s.hull_m.front().data(), static_cast<int>(sizeof(Vec3)), static_cast<int>(s.hull_m.size()),
                                     s.margin_m + s.gap_m, 0.25);
  if (hull.vertices.size() < 4) throw std::invalid_argument(fmt::format("World::add_body: body {}'s hull is flat", s.id));
  b->shape = std::make_unique<btConvexHullShape>(&hull.vertices[0][0], hull.vertices.size(), static_cast<int>(sizeof(btVector3)));
  // GJK's support query is linear in the hull's vertices (fracture pieces have fine surfaces).
  if (s.max_hull_vertices > 0 && b->shape->getNumPoints() > s.max_hull_vertices) {
    b->shape->setMargin(0);
    btShapeHull reduced(b->shape.get());
    reduced.buildHull(0);
    b->shape = std::make_unique<btConvexHullShape>(&reduced.getVertexPointer()[0][0], reduced.numVertices(), static_cast<int>(sizeof(btVector3)));
  }
  b->shape->setMargin(std::max(0.0, shrunk - s.gap_m));
  b->motion = std::make_unique<btDefaultMotionState>(transform_of(s.initial.pose));
  btRigidBody::btRigidBodyConstructionInfo info(s.mass_kg, b->motion.get(), b->shape.get(), bt(s.principal_moments_kg_m2));
  info.m_friction = s.friction;
  info.m_restitution = s.restitution;
  b->body = std::make_unique<btRigidBody>(info);
  b->body->setLinearVelocity(bt(s.initial.velocity_m_s));
  b->body->setAngularVelocity(bt(s.initial.angular_velocity_rad_s));
  // Sleeping bodies keep their last impulses in their manifolds and stop being solved: the record
  // must see every step, so no body sleeps.
  b->body->setActivationState(DISABLE_DEACTIVATION);
  b->body->setUserIndex(s.id);
  impl_->world.addRigidBody(b->body.get());
  bodies_[s.id] = std::move(b);
}

void World::remove_body(int id) {
  auto it = bodies_.find(id);
  if (it == bodies_.end()) throw std::invalid_argument(fmt::format("World::remove_body: no body {}", id));
  for (auto p = ignored_.begin(); p != ignored_.end();)
    if (p->first == id || p->second == id) {
      const int other = p->first == id ? p->second : p->first;
      bodies_.at(other)->body->setIgnoreCollisionCheck(it->second->body.get(), false);
      p = ignored_.erase(p);
    } else {
      ++p;
    }
  impl_->world.removeRigidBody(it->second->body.get());
  bodies_.erase(it);
}

void World::ignore_until_apart(int a, int b) {
  btRigidBody& ra = *bodies_.at(a)->body;
  btRigidBody& rb = *bodies_.at(b)->body;
  ra.setIgnoreCollisionCheck(&rb, true);
  rb.setIgnoreCollisionCheck(&ra, true);
  ignored_.insert({std::min(a, b), std::max(a, b)});
}

BodyState World::state(int id) const {
  auto it = bodies_.find(id);
  if (it == bodies_.end()) throw std::invalid_argument(fmt::format("World::state: no body {}", id));
  const btRigidBody& r = *it->second->body;
  return {pose_of(r.getWorldTransform()), vec(r.getLinearVelocity()), vec(r.getAngularVelocity())};
}

BodyState World::start_state(int id) const {
  auto it = bodies_.find(id);
  if (it == bodies_.end()) throw std::invalid_argument(fmt::format("World::start_state: no body {}", id));
  return {pose_of(it->second->start), vec(it->second->v_start), vec(it->second->w_start)};
}

void World::step() {
  for (auto& [id, b] : bodies_) {
    b->start = b->body->getWorldTransform();
    b->v_start = b->body->getLinearVelocity();
    b->w_start = b->body->getAngularVelocity();
  }
  // maxSubSteps = 0: exactly one step of dt_s (no interpolation, no accumulator).
  impl_->world.stepSimulation(impl_->options.dt_s, 0, impl_->options.dt_s);
  for (auto p = ignored_.begin(); p != ignored_.end();) {
    btRigidBody& ra = *bodies_.at(p->first)->body;
    btRigidBody& rb = *bodies_.at(p->second)->body;
    btVector3 a_lo, a_hi, b_lo, b_hi;
    ra.getAabb(a_lo, a_hi);
    rb.getAabb(b_lo, b_hi);
    if (TestAabbAgainstAabb2(a_lo, a_hi, b_lo, b_hi)) {
      ++p;
      continue;
    }
    ra.setIgnoreCollisionCheck(&rb, false);
    rb.setIgnoreCollisionCheck(&ra, false);
    p = ignored_.erase(p);
  }
  contacts_.clear();
  btDispatcher& d = impl_->dispatcher;
  for (int m = 0; m < d.getNumManifolds(); ++m) {
    btPersistentManifold* manifold = d.getManifoldByIndexInternal(m);
    const int id0 = manifold->getBody0()->getUserIndex(), id1 = manifold->getBody1()->getUserIndex();
    // Scene events put the ground second: the normal and impulse are flipped for a ground-first pair.
    const bool flip = id0 == 0;
    const Body* b0 = id0 ? bodies_.at(id0).get() : nullptr;
    const Body* b1 = id1 ? bodies_.at(id1).get() : nullptr;
    for (int k = 0; k < manifold->getNumContacts(); ++k) {
      btManifoldPoint& p = manifold->getContactPoint(k);
      // Bullet's normal points from body 1 to body 0, and body 0 receives +impulse.
      const btVector3 j0 = p.m_normalWorldOnB * p.m_appliedImpulse + p.m_lateralFrictionDir1 * p.m_appliedImpulseLateral1 +
                           p.m_lateralFrictionDir2 * p.m_appliedImpulseLateral2;
      if (j0.length2() == 0) continue;
      const btVector3 at = (p.getPositionWorldOnA() + p.getPositionWorldOnB()) * 0.5;
      auto velocity = [&](const Body* b) {
        return b ? b->v_start + b->w_start.cross(at - b->start.getOrigin()) : btVector3(0, 0, 0);
      };
      ContactSample c;
      c.a = flip ? id1 : id0;
      c.b = flip ? id0 : id1;
      c.point_m = vec(at);
      c.impulse_n_s = vec(flip ? -j0 : j0);
      c.normal = vec(flip ? -p.m_normalWorldOnB : p.m_normalWorldOnB);
      c.approach_speed_m_s = -(velocity(b0) - velocity(b1)).dot(p.m_normalWorldOnB);
      if (p.getDistance() > 0 && c.approach_speed_m_s > 0)
        c.touch_after_s = std::min(impl_->options.dt_s, p.getDistance() / c.approach_speed_m_s);
      const Body* a = flip ? b1 : b0;
      const Body* b = flip ? b0 : b1;
      c.pose_a = pose_of(a->start);
      if (b) c.pose_b = pose_of(b->start);
      contacts_.push_back(c);
    }
  }
  ++steps_;
}

}  // namespace clatter::sim
