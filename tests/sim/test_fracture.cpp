// clatter-sim's fracture (sim/fracture.cpp, 003 section 3) against conservation laws: at a
// fracture the pieces' masses sum to the body's, their momentum and angular momentum are the
// body's (the fracture impulses are internal forces), their kinetic energy grows by exactly
// E_S - E_F, and G_c A_F <= eta E_S; without fracture impulses the pieces keep the body's motion.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>

#include "core/errors.hpp"
#include "core/rotation.hpp"
#include "io/materials.hpp"
#include "kernels/fracture/impulses.hpp"
#include "tests/reference/tet_inertia.hpp"
#include "kernels/fracture/tet_mesh.hpp"
#include "sim/fracture.hpp"
#include "sim/voronoi.hpp"

namespace clatter::sim {
namespace {

namespace kf = kernels::fracture;

// A glass slab 0.2 x 0.1 x 0.01 m centred on its centre of mass, in its own (principal) frame.
kf::TetMesh slab_mesh() {
  const Piece box = voronoi_pieces({-0.1, -0.05, -0.005}, {0.1, 0.05, 0.005}, {}, {{0, 0, 0}}).front();
  return kf::tetrahedralize(box.vertices_m, box.triangles, 0.006);
}

Eigen::Vector3d e(const Vec3& v) { return {v[0], v[1], v[2]}; }
Eigen::Matrix3d e(const kf::Mat3& m) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m[i][j];
  return r;
}
Eigen::Matrix3d rotation(const io::Pose& p) {
  Eigen::Matrix3d r;
  for (int j = 0; j < 3; ++j) {
    Vec3 u{};
    u[j] = 1;
    r.col(j) = e(rotate(p.orientation_wxyz, u));
  }
  return r;
}

struct Momenta {
  double mass_kg = 0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), l = Eigen::Vector3d::Zero();  // l about `about`
  double kinetic_j = 0;
};

// A slab moving and spinning, struck hard on one corner from below in one step.
struct Struck {
  kf::TetMesh mesh = slab_mesh();
  model::Material glass = io::find_material(io::builtin_materials(), "glass", "test");
  BodyState state;
  std::vector<ContactSample> contacts;
  Struck() {
    state.pose.position_m = {0.3, -0.2, 0.05};
    const double a = 0.4;  // turned about (1, 2, 2)/3
    state.pose.orientation_wxyz = {std::cos(a / 2), std::sin(a / 2) / 3, 2 * std::sin(a / 2) / 3, 2 * std::sin(a / 2) / 3};
    state.velocity_m_s = {0.5, -0.3, -2.0};
    state.angular_velocity_rad_s = {3.0, -1.0, 2.0};
    ContactSample c;
    c.a = 1;
    c.b = 0;
    c.pose_a = state.pose;
    c.point_m = add(state.pose.position_m, rotate(state.pose.orientation_wxyz, {0.099, 0.049, -0.005}));
    c.impulse_n_s = rotate(state.pose.orientation_wxyz, {0.0, 0.0, 3.0});  // 30 kN over 0.1 ms
    c.normal = {0, 0, 1};
    contacts.push_back(c);
  }
  // The body's momenta before (a rigid body: its inertia from its tetrahedra, in the world).
  Momenta before() const {
    const kf::PieceInertia b = reference::tet_mesh_inertia(mesh, glass.rho_kg_m3);
    const Eigen::Matrix3d r = rotation(state.pose);
    const Eigen::Matrix3d inertia = r * e(b.inertia_kg_m2) * r.transpose();
    Momenta m;
    m.mass_kg = b.mass_kg;
    m.p = b.mass_kg * e(state.velocity_m_s);
    m.l = inertia * e(state.angular_velocity_rad_s);
    m.kinetic_j = 0.5 * b.mass_kg * e(state.velocity_m_s).squaredNorm() +
                  0.5 * e(state.angular_velocity_rad_s).dot(inertia * e(state.angular_velocity_rad_s));
    return m;
  }
};

// The pieces' momenta about the body's centre of mass (their meshes are in the body's frame).
Momenta after(const Fracture& f, const BodyState& body, double rho) {
  const Eigen::Matrix3d r = rotation(body.pose);
  Momenta m;
  for (const NewPiece& p : f.pieces) {
    const kf::PieceInertia i = reference::tet_mesh_inertia(p.mesh, rho);
    const Eigen::Vector3d c = r * e(i.centre_m);  // from the body's centre, world axes
    const Eigen::Matrix3d inertia = r * e(i.inertia_kg_m2) * r.transpose();
    const Eigen::Vector3d v = e(p.velocity_m_s), w = e(p.angular_velocity_rad_s);
    m.mass_kg += i.mass_kg;
    m.p += i.mass_kg * v;
    m.l += inertia * w + c.cross(i.mass_kg * v);
    m.kinetic_j += 0.5 * i.mass_kg * v.squaredNorm() + 0.5 * w.dot(inertia * w);
  }
  return m;
}

TEST(SimFracture, PiecesConserveMassMomentumAndGainTheReleasedEnergy) {
  Struck s;
  FractureSettings settings;
  Breakables b(settings);
  b.insert(1, s.mesh, s.glass);
  const std::optional<Fracture> f = b.check(1, s.contacts, s.state, 1e-4, 0.1, 1e9);
  ASSERT_TRUE(f.has_value()) << "a 30 kN corner blow must break a 1 cm glass slab";
  const io::SceneFracture& r = f->record;
  ASSERT_GE(f->pieces.size(), 2u);
  std::printf("  struck slab: %zu pieces, sigma_1 %.3g MPa, E_S %.4g J, E_F %.4g J (A_F %.4g m^2), Delta E_K %.4g J, tau %.3g us\n",
              f->pieces.size(), r.max_principal_pa * 1e-6, r.strain_energy_j, r.fracture_energy_j, r.fracture_area_m2,
              r.kinetic_energy_gained_j, r.tau_s * 1e6);
  EXPECT_LE(r.fracture_energy_j, settings.eta * r.strain_energy_j);
  EXPECT_NEAR(r.fracture_energy_j, s.glass.fracture_energy_j_m2.value() * r.fracture_area_m2, 1e-12 * r.fracture_energy_j);
  const Momenta m0 = s.before(), m1 = after(*f, s.state, s.glass.rho_kg_m3);
  EXPECT_NEAR(m1.mass_kg, m0.mass_kg, 1e-12 * m0.mass_kg);
  const double p_scale = m0.mass_kg * (e(s.state.velocity_m_s).norm() + 0.2 * e(s.state.angular_velocity_rad_s).norm());
  EXPECT_LT((m1.p - m0.p).norm(), 1e-10 * p_scale);
  EXPECT_LT((m1.l - m0.l).norm(), 1e-10 * p_scale * 0.2);
  // Delta E_K = E_S - E_F to 1 % (the bound; it is exact up to rounding).
  const double gained = m1.kinetic_j - m0.kinetic_j;
  EXPECT_NEAR(gained, r.strain_energy_j - r.fracture_energy_j, 0.01 * (r.strain_energy_j - r.fracture_energy_j));
  EXPECT_NEAR(r.kinetic_energy_gained_j, gained, 1e-9 * m0.kinetic_j);
  // The scene's impulses are the pieces' momentum changes.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const NewImpulse& i : f->impulses) sum += e(i.impulse_n_s);
  EXPECT_LT(sum.norm(), 1e-9 * p_scale);
}

// Fig. 5's inset: without fracture impulses the pieces move as the body did, gaining nothing.
TEST(SimFracture, WithoutImpulsesPiecesKeepTheBodysMotion) {
  Struck s;
  FractureSettings settings;
  settings.impulses = false;
  Breakables b(settings);
  b.insert(1, s.mesh, s.glass);
  const std::optional<Fracture> f = b.check(1, s.contacts, s.state, 1e-4, 0.1, 1e9);
  ASSERT_TRUE(f.has_value());
  const Momenta m0 = s.before(), m1 = after(*f, s.state, s.glass.rho_kg_m3);
  EXPECT_NEAR(m1.kinetic_j, m0.kinetic_j, 1e-9 * m0.kinetic_j);
  EXPECT_EQ(f->record.kinetic_energy_gained_j, 0);
  EXPECT_TRUE(f->impulses.empty() || f->record.tau_s == 0);
}

// The same blow with little energy to take: the stress is scaled to the absorbed energy, and a
// slab that cannot store enough to pass its strength does not break.
TEST(SimFracture, TheAbsorbedEnergyBoundsTheStress) {
  Struck s;
  Breakables b(FractureSettings{});
  b.insert(1, s.mesh, s.glass);
  EXPECT_FALSE(b.check(1, s.contacts, s.state, 1e-4, 0.1, 1e-3).has_value());
  EXPECT_EQ(b.stats().energy_bounded, 1u);
  EXPECT_EQ(b.stats().fractures, 0u);
  // Less than the smallest tetrahedron holds at the strength: not even solved.
  EXPECT_FALSE(b.check(1, s.contacts, s.state, 1e-4, 0.1, 1e-9).has_value());
  EXPECT_EQ(b.stats().skipped, 1u);
  EXPECT_EQ(b.stats().stress_solves, 1u);
}

// A blow far below the strength breaks nothing, and a body without fracture data is refused.
TEST(SimFracture, WeakBlowsAndUnbreakableMaterials) {
  Struck s;
  s.contacts[0].impulse_n_s = scale(s.contacts[0].impulse_n_s, 1e-4);  // 3 N
  Breakables b(FractureSettings{});
  b.insert(1, s.mesh, s.glass);
  EXPECT_FALSE(b.check(1, s.contacts, s.state, 1e-4, 0.1, 1e9).has_value());
  EXPECT_EQ(b.stats().stress_solves, 1u);
  const model::Material steel = io::find_material(io::builtin_materials(), "steel", "test");
  EXPECT_THROW(b.insert(2, s.mesh, steel), InputError);
}

}  // namespace
}  // namespace clatter::sim
