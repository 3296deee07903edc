// Multiplets by symmetry (kernels/modal/multiplets.hpp) on analytic fields sampled on curved
// ellipsoid surface meshes (kernels/fem/ellipsoid_mesh.hpp). The fields and their orders are
// independent of the code: a rigid rotation about an axis is invariant under rotations about that
// axis (m = 0) and the three rotations transform as a vector (degree 1); the gradient of a degree-2
// harmonic polynomial transforms like the polynomial (R grad f(R^T x) = grad (f o R^T)), so grad(xy)
// and grad(x^2 - y^2) have |m| = 2 about z, grad(xz), grad(yz) |m| = 1, grad(2z^2 - x^2 - y^2)
// m = 0, and all five degree n = 2.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <functional>
#include <random>

#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/modal/multiplets.hpp"
#include "tests/reference/random_orthogonal.hpp"

namespace {
using namespace clatter::kernels;
using modal::SymmetryKind;
using Field = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

using clatter::reference::random_orthogonal;

Field rotation(int axis) {
  return [axis](const Eigen::Vector3d& x) { return Eigen::Vector3d::Unit(axis).cross(x); };
}
// grad of x_i x_j (i != j) and of x_i^2 - x_j^2: harmonic, degree 2.
Field grad_product(int i, int j) {
  return [i, j](const Eigen::Vector3d& x) {
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    g(i) = x(j);
    g(j) = x(i);
    return g;
  };
}
Field grad_difference(int i, int j) {
  return [i, j](const Eigen::Vector3d& x) {
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    g(i) = 2 * x(i);
    g(j) = -2 * x(j);
    return g;
  };
}
// grad (2 x_a^2 - x_b^2 - x_c^2): m = 0 about axis a.
Field grad_zonal(int a) {
  return [a](const Eigen::Vector3d& x) {
    Eigen::Vector3d g = -2 * x;
    g(a) = 4 * x(a);
    return g;
  };
}

struct Surface {
  std::vector<std::array<double, 3>> nodes;
  std::vector<std::array<std::int32_t, 6>> faces;
};

Surface surface(const std::array<double, 3>& axes, double h) {
  const auto mesh = fem::mesh_ellipsoid({axes, h});
  Surface s;
  for (Eigen::Index i = 0; i < mesh.mesh.nodes_m.cols(); ++i)
    s.nodes.push_back({mesh.mesh.nodes_m(0, i), mesh.mesh.nodes_m(1, i), mesh.mesh.nodes_m(2, i)});
  for (const auto& f : mesh.boundary) {
    std::array<std::int32_t, 6> g{};
    for (std::size_t k = 0; k < 6; ++k) g[k] = f[k];
    s.faces.push_back(g);
  }
  return s;
}

// The modes of one cluster: each group of fields (one irreducible subspace) mixed by its own
// orthogonal matrix, the groups in the given order.
std::vector<double> sample(const Surface& s, const std::vector<std::vector<Field>>& groups, unsigned seed) {
  std::vector<double> shapes;
  for (const auto& group : groups) {
    const auto n = static_cast<int>(group.size());
    const Eigen::MatrixXd q = random_orthogonal(n, seed++);
    for (int j = 0; j < n; ++j)
      for (const auto& p : s.nodes) {
        const Eigen::Vector3d x(p[0], p[1], p[2]);
        Eigen::Vector3d u = Eigen::Vector3d::Zero();
        for (int i = 0; i < n; ++i) u += q(i, j) * group[static_cast<std::size_t>(i)](x);
        shapes.insert(shapes.end(), {u(0), u(1), u(2)});
      }
  }
  return shapes;
}

std::vector<int> sizes(const modal::Multiplets& m) {
  std::vector<int> out(static_cast<std::size_t>(*std::max_element(m.multiplet.begin(), m.multiplet.end()) + 1));
  for (int g : m.multiplet) ++out[static_cast<std::size_t>(g)];
  return out;
}

TEST(Multiplets, SymmetryFromAxes) {
  EXPECT_EQ(modal::ellipsoid_symmetry({1, 1, 1}).kind, SymmetryKind::sphere);
  EXPECT_EQ(modal::ellipsoid_symmetry({0.5, 1, 1}).kind, SymmetryKind::spheroid);
  EXPECT_EQ(modal::ellipsoid_symmetry({0.5, 1, 1}).axis, 0);
  EXPECT_EQ(modal::ellipsoid_symmetry({1, 1, 2}).axis, 2);
  EXPECT_EQ(modal::ellipsoid_symmetry({1, 2, 3}).kind, SymmetryKind::none);
  EXPECT_EQ(modal::ellipsoid_symmetry({1, 1 + 1e-6, 3}).kind, SymmetryKind::none);
}

// A sphere cluster of 8 modes: the 3 rotations (n = 1) and the 5 harmonic gradients (n = 2), in
// the order n = 2, n = 1, n = 2 ... (3 + 5 split by "frequency"): one triplet and one quintet.
TEST(Multiplets, SphereDegreesFromTheCasimir) {
  const auto s = surface({1, 1, 1}, 0.35);
  const std::vector<Field> n1{rotation(0), rotation(1), rotation(2)};
  const std::vector<Field> n2{grad_product(0, 1), grad_product(1, 2), grad_product(0, 2), grad_difference(0, 1),
                              grad_zonal(2)};
  const auto shapes = sample(s, {n2, n1}, 3);
  // Interleave: modes 0..4 are n = 2, 5..7 n = 1; reorder to 2 1 2 2 1 2 1 2.
  const std::vector<int> order{0, 5, 1, 2, 6, 3, 7, 4};
  const std::size_t per_mode = s.nodes.size() * 3;
  std::vector<double> mixed;
  for (int i : order) mixed.insert(mixed.end(), shapes.begin() + static_cast<long>(i * per_mode),
                                   shapes.begin() + static_cast<long>((i + 1) * per_mode));
  const std::vector<std::int32_t> cluster(8, 0);
  const auto m = modal::find_multiplets(s.nodes, s.faces, mixed, cluster, modal::ellipsoid_symmetry({1, 1, 1}));
  EXPECT_EQ(m.order, (std::vector<std::int32_t>{2, 1, 2, 2, 1, 2, 1, 2}));
  EXPECT_EQ(m.multiplet, (std::vector<std::int32_t>{0, 1, 0, 0, 1, 0, 1, 0}));
  EXPECT_EQ(m.incomplete, 0);
  EXPECT_LT(m.order_defect, 0.02);
  std::printf("sphere n = 1, 2: order defect %.2e\n", m.order_defect);
}

// An oblate spheroid (axis x): rotations about x (m = 0), y and z (|m| = 1); the five harmonic
// gradients about x: zonal (m = 0), xy and xz (|m| = 1), yz and y^2 - z^2 (|m| = 2). Clusters:
// {rot_x} {rot_y rot_z, grad xy, grad xz} {grad zonal, grad yz, grad y^2 - z^2}.
TEST(Multiplets, SpheroidDoubletsAndSingles) {
  const std::array<double, 3> axes{0.5, 1, 1};
  const auto s = surface(axes, 0.3);
  const auto shapes = sample(s, {{rotation(0)}, {rotation(1), rotation(2)}, {grad_product(0, 1), grad_product(0, 2)},
                                 {grad_zonal(0)}, {grad_product(1, 2), grad_difference(1, 2)}}, 11);
  const std::vector<std::int32_t> cluster{0, 1, 1, 1, 1, 2, 2, 2};
  const auto m = modal::find_multiplets(s.nodes, s.faces, shapes, cluster, modal::ellipsoid_symmetry(axes));
  EXPECT_EQ(m.order, (std::vector<std::int32_t>{0, 1, 1, 1, 1, 0, 2, 2}));
  EXPECT_EQ(m.multiplet, (std::vector<std::int32_t>{0, 1, 1, 2, 2, 3, 4, 4}));
  EXPECT_EQ(sizes(m), (std::vector<int>{1, 2, 2, 1, 2}));
  EXPECT_EQ(m.incomplete, 0);
  EXPECT_LT(m.order_defect, 0.05);
  std::printf("spheroid m = 0, 1, 2: order defect %.2e\n", m.order_defect);
}

// A triaxial ellipsoid has no degeneracy: every mode its own multiplet, no order.
TEST(Multiplets, TriaxialHasOnlySingles) {
  const std::array<double, 3> axes{0.5, 0.75, 1};
  const auto s = surface(axes, 0.3);
  const auto shapes = sample(s, {{rotation(0), rotation(1)}}, 5);
  const auto m = modal::find_multiplets(s.nodes, s.faces, shapes, std::vector<std::int32_t>{0, 0},
                                        modal::ellipsoid_symmetry(axes));
  EXPECT_EQ(m.multiplet, (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(m.order, (std::vector<std::int32_t>{-1, -1}));
}

// What it reports when a cluster is not a whole symmetric subspace: one member of a doublet alone
// is an incomplete multiplet; a field of mixed degree (x e_x = grad x^2 / 2, degrees 0 and 2) has
// no integer degree.
TEST(Multiplets, FlagsBrokenMultiplets) {
  const std::array<double, 3> axes{0.5, 1, 1};
  const auto s = surface(axes, 0.3);
  const auto half = modal::find_multiplets(s.nodes, s.faces, sample(s, {{grad_product(0, 1)}}, 1),
                                           std::vector<std::int32_t>{0}, modal::ellipsoid_symmetry(axes));
  EXPECT_EQ(half.incomplete, 1);
  EXPECT_EQ(half.order, (std::vector<std::int32_t>{1}));
  const auto sphere = surface({1, 1, 1}, 0.35);
  const Field mixed = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x(0), 0, 0); };
  const auto m = modal::find_multiplets(sphere.nodes, sphere.faces, sample(sphere, {{mixed}}, 1),
                                        std::vector<std::int32_t>{0}, modal::ellipsoid_symmetry({1, 1, 1}));
  EXPECT_GT(m.order_defect, 0.2);
  std::printf("x e_x on a sphere: degree %.3f from an integer\n", m.order_defect);
}

}  // namespace
