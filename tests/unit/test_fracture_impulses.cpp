// 003 section 3.3's fracture impulses against conservation laws and a closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/fracture/impulses.hpp"
#include "tests/reference/tet_inertia.hpp"

namespace clatter::kernels::fracture {
namespace {

// Two unit-density cubes of side 1 m, [-1, 0] x [0, 1]^2 (piece 0) and [0, 1] x [0, 1]^2
// (piece 1), meeting on x = 0: the interface as two triangles per side, each outward from its piece.
std::vector<FractureTriangle> cube_interface(int tet) {
  const Vec3 p00{0, 0, 0}, p10{0, 1, 0}, p11{0, 1, 1}, p01{0, 0, 1};
  std::vector<FractureTriangle> f;
  // Outward from piece 0 is +x: counter-clockwise seen from +x.
  f.push_back({{p00, p10, p11}, 0, 1, tet});
  f.push_back({{p00, p11, p01}, 0, 1, tet});
  // Outward from piece 1 is -x: the same triangles reversed.
  f.push_back({{p00, p11, p10}, 1, 0, tet});
  f.push_back({{p00, p01, p11}, 1, 0, tet});
  return f;
}

PieceInertia unit_cube(double x_centre) {
  PieceInertia p;
  p.mass_kg = 1;
  p.centre_m = {x_centre, 0.5, 0.5};
  for (int i = 0; i < 3; ++i) p.inertia_kg_m2[i][i] = 1.0 / 6;  // m (a^2 + a^2) / 12
  return p;
}

// Uniform tension s across the interface: each cube gets |S| = s A away from the other and no
// torque; 1/2 * 2 * (tau s)^2 = Delta E gives tau = sqrt(Delta E) / s (m = 1, A = 1).
TEST(FractureImpulses, TensionPushesTheHalvesApartWithTheEnergyReleased) {
  const double s = 2e6, released = 0.5;
  Mat3 sigma{};
  sigma[0][0] = s;
  const FractureImpulses out = fracture_impulses(cube_interface(0), {sigma}, {unit_cube(-0.5), unit_cube(0.5)},
                                                 {Vec3{}, Vec3{}}, {Vec3{}, Vec3{}}, released);
  EXPECT_NEAR(out.tau_s, std::sqrt(released) / s, 1e-15);
  EXPECT_NEAR(out.dv_m_s[0][0], -std::sqrt(released), 1e-12);  // piece 0 moves to -x, away from piece 1
  EXPECT_NEAR(out.dv_m_s[1][0], std::sqrt(released), 1e-12);
  for (int d = 0; d < 2; ++d)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(out.dw_rad_s[d][k], 0, 1e-12);
  EXPECT_NEAR(out.kinetic_energy_gained_j, released, 1e-12 * released);
  ASSERT_EQ(out.interfaces.size(), 2u);
  EXPECT_NEAR(out.interfaces[0].area_m2, 1, 1e-15);
  EXPECT_NEAR(out.interfaces[0].point_m[1], 0.5, 1e-15);
}

// A general stress (shear included) on a body already moving and spinning: the impulses sum to
// zero force and zero torque about the body's centre of mass, and the kinetic energy gained is
// exactly the energy released (the quadratic's linear term is not zero here: the pieces move).
TEST(FractureImpulses, ConserveMomentumAndDeliverTheReleasedEnergy) {
  Mat3 sigma{{{3e6, 1e6, -2e5}, {1e6, -5e5, 7e5}, {-2e5, 7e5, 1.5e6}}};
  const std::vector<PieceInertia> pieces{unit_cube(-0.5), unit_cube(0.5)};
  // A rigid motion of the two-cube body about its centre (0, 0.5, 0.5).
  const Vec3 v{0.3, -1.0, 2.0}, w{4.0, -2.0, 1.0}, c{0, 0.5, 0.5};
  std::vector<Vec3> vd, wd;
  for (const auto& p : pieces) vd.push_back(add(v, cross(w, sub(p.centre_m, c)))), wd.push_back(w);
  const double released = 0.37;
  const FractureImpulses out = fracture_impulses(cube_interface(0), {sigma}, pieces, vd, wd, released);
  ASSERT_GT(out.tau_s, 0);
  Vec3 force{}, torque{};
  for (int d = 0; d < 2; ++d) {
    force = add(force, out.force_n[d]);
    torque = add(torque, add(out.torque_nm[d], cross(sub(pieces[d].centre_m, c), out.force_n[d])));
  }
  const double scale_n = std::abs(sigma[0][0]);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(force[k], 0, 1e-12 * scale_n);
    EXPECT_NEAR(torque[k], 0, 1e-12 * scale_n);
  }
  EXPECT_NEAR(out.kinetic_energy_gained_j, released, 1e-9 * released);
  // Linear and angular momentum (about c) of the pieces are unchanged.
  Vec3 dp{}, dl{};
  for (int d = 0; d < 2; ++d) {
    dp = add(dp, scale(out.dv_m_s[d], pieces[d].mass_kg));
    Vec3 iw{};
    for (int i = 0; i < 3; ++i) iw[i] = dot(Vec3{pieces[d].inertia_kg_m2[i][0], pieces[d].inertia_kg_m2[i][1], pieces[d].inertia_kg_m2[i][2]}, out.dw_rad_s[d]);
    dl = add(dl, add(iw, cross(sub(pieces[d].centre_m, c), scale(out.dv_m_s[d], pieces[d].mass_kg))));
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(dp[k], 0, 1e-12);
    EXPECT_NEAR(dl[k], 0, 1e-12);
  }
}

TEST(FractureImpulses, NoEnergyOrNoStressChangesNothing) {
  Mat3 sigma{};
  sigma[0][0] = 1e6;
  const auto none = fracture_impulses(cube_interface(0), {sigma}, {unit_cube(-0.5), unit_cube(0.5)}, {Vec3{}, Vec3{}}, {Vec3{}, Vec3{}}, 0);
  EXPECT_EQ(none.tau_s, 0);
  EXPECT_EQ(none.dv_m_s[0][0], 0);
  const auto unstressed = fracture_impulses(cube_interface(0), {Mat3{}}, {unit_cube(-0.5), unit_cube(0.5)}, {Vec3{}, Vec3{}}, {Vec3{}, Vec3{}}, 1);
  EXPECT_EQ(unstressed.tau_s, 0);
}

// The inertia of a tetrahedral cube against m a^2 / 6 on the diagonal.
TEST(FractureImpulses, TetMeshInertiaOfACube) {
  TetMesh cube;
  for (int k = 0; k < 8; ++k) cube.nodes_m.push_back({double(k & 1), double(k >> 1 & 1), double(k >> 2 & 1)});
  // Six tetrahedra around the diagonal 0-7.
  const int paths[6][2] = {{1, 3}, {3, 2}, {2, 6}, {6, 4}, {4, 5}, {5, 1}};
  for (const auto& p : paths) {
    std::array<int, 4> t{0, p[0], p[1], 7};
    cube.tets.push_back(t);
    if (tet_volume_m3(cube, static_cast<int>(cube.tets.size()) - 1) < 0) std::swap(cube.tets.back()[2], cube.tets.back()[3]);
  }
  const PieceInertia p = reference::tet_mesh_inertia(cube, 2.0);
  EXPECT_NEAR(p.mass_kg, 2.0, 1e-14);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(p.centre_m[i], 0.5, 1e-14);
    EXPECT_NEAR(p.inertia_kg_m2[i][i], 2.0 / 6, 1e-14);
    EXPECT_NEAR(p.inertia_kg_m2[i][(i + 1) % 3], 0, 1e-14);
  }
}

}  // namespace
}  // namespace clatter::kernels::fracture
