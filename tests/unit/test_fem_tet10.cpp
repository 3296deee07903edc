// The 10-node tetrahedron (kernels/fem/): shape functions, quadrature, element matrices, and patch
// tests on a small assembled mesh, each against something computed independently of the element.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <utility>

#include "kernels/fem/assembly.hpp"
#include "kernels/fem/tet10.hpp"

using namespace clatter::kernels::fem;

namespace {

clatter::model::Material steel_material() {
  clatter::model::Material m;
  m.name = "steel", m.youngs_pa = 200e9, m.poisson = 0.3, m.rho_kg_m3 = 7850;
  return m;
}
const clatter::model::Material kSteel = steel_material();
constexpr double kRhoKgM3 = 7800;

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// A generic straight element (not aligned with the axes), metres.
Tet10Coords generic_tet() {
  Eigen::Matrix<double, 3, 4> v;
  v << 0.01, 0.12, 0.02, 0.03,  //
      0.00, 0.01, 0.09, 0.02,   //
      0.02, 0.00, 0.01, 0.11;
  return tet10_straight(v);
}

// The same with mid-node 4 (edge 01) pushed off its edge, outwards and along it.
Tet10Coords curved_tet() {
  Tet10Coords x = generic_tet();
  x.col(4) += Eigen::Vector3d(0.006, -0.012, -0.009);
  return x;
}

// The 6 rigid-body motions sampled at the nodes, one per column.
Eigen::Matrix<double, kTet10Dofs, 6> rigid_motions(const Tet10Coords& x) {
  Eigen::Matrix<double, kTet10Dofs, 6> r = Eigen::Matrix<double, kTet10Dofs, 6>::Zero();
  for (int i = 0; i < kTet10Nodes; ++i)
    for (int c = 0; c < 3; ++c) {
      r(3 * i + c, c) = 1;
      r.block<3, 1>(3 * i, 3 + c) = Eigen::Vector3d::Unit(c).cross(Eigen::Vector3d(x.col(i)));
    }
  return r;
}

}  // namespace

TEST(Tet10Shape, PartitionOfUnityAndKronecker) {
  for (int j = 0; j < kTet10Nodes; ++j) {
    const Tet10Shape n = tet10_shape(tet10_reference_node(j));
    for (int i = 0; i < kTet10Nodes; ++i) EXPECT_NEAR(n(i), i == j ? 1.0 : 0.0, 1e-15) << i << " at node " << j;
  }
  for (const RefPoint& p : keast_degree5().points) {
    EXPECT_NEAR(tet10_shape(p).sum(), 1.0, 1e-15);
    EXPECT_LT(tet10_shape_gradient(p).colwise().sum().norm(), 1e-14);
  }
}

TEST(Tet10Shape, GradientMatchesFiniteDifferences) {
  const RefPoint p = {0.21, 0.17, 0.33};
  const Tet10Gradient g = tet10_shape_gradient(p);
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    RefPoint up = p, down = p;
    up[k] += h;
    down[k] -= h;
    const Tet10Shape fd = (tet10_shape(up) - tet10_shape(down)) / (2 * h);
    EXPECT_LT((fd - g.col(k)).norm(), 1e-9) << "direction " << k;
  }
}

TEST(Tet10Quadrature, RulesIntegrateMonomialsExactlyUpToTheirDegree) {
  // integral over the unit tetrahedron of xi^a eta^b zeta^c = a! b! c! / (a + b + c + 3)!
  const TetQuadrature high = collapsed_gauss(9);
  for (const TetQuadrature* rule : {&keast_degree2(), &keast_degree5(), &high}) {
    for (int a = 0; a <= rule->degree; ++a)
      for (int b = 0; a + b <= rule->degree; ++b)
        for (int c = 0; a + b + c <= rule->degree; ++c) {
          double sum = 0;
          for (std::size_t q = 0; q < rule->points.size(); ++q) {
            const RefPoint& p = rule->points[q];
            sum += rule->weights[q] * std::pow(p[0], a) * std::pow(p[1], b) * std::pow(p[2], c);
          }
          const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
          EXPECT_NEAR(sum, exact, 1e-14 * exact) << "degree " << rule->degree << ": " << a << b << c;
        }
    for (double w : rule->weights) EXPECT_GT(w, 0);
  }
  EXPECT_EQ(keast_degree2().points.size(), 4u);
  EXPECT_EQ(keast_degree5().points.size(), 15u);
}

TEST(Tet10Stiffness, RigidMotionsSpanTheNullSpaceAndTheRankIs24) {
  for (const Tet10Coords& x : {generic_tet(), curved_tet()}) {
    const Tet10Matrix k = tet10_stiffness(x, kSteel);
    const Eigen::Matrix<double, kTet10Dofs, 6> r = rigid_motions(x);
    for (int m = 0; m < 6; ++m) EXPECT_LT((k * r.col(m)).norm() / (k.norm() * r.col(m).norm()), 1e-12) << m;
    const Eigen::SelfAdjointEigenSolver<Tet10Matrix> eig(k);
    const double largest = eig.eigenvalues().maxCoeff();
    int zero = 0, positive = 0;
    for (double lambda : eig.eigenvalues()) {
      if (std::abs(lambda) < 1e-12 * largest) ++zero;
      if (lambda > 1e-8 * largest) ++positive;
    }
    EXPECT_EQ(zero, 6);
    EXPECT_EQ(positive, 24);
  }
}

TEST(Tet10Stiffness, SymmetricAndPositiveSemiDefinite) {
  const Tet10Matrix k = tet10_stiffness(curved_tet(), kSteel);
  EXPECT_EQ((k - k.transpose()).norm(), 0.0);
  const Eigen::SelfAdjointEigenSolver<Tet10Matrix> eig(k);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * eig.eigenvalues().maxCoeff());
}

TEST(Tet10Mass, PositiveDefiniteWithTheTotalMass) {
  for (const Tet10Coords& x : {generic_tet(), curved_tet()}) {
    const Tet10Matrix m = tet10_mass(x, kRhoKgM3);
    EXPECT_LT((m - m.transpose()).norm(), 1e-15 * m.norm());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Tet10Matrix>(m).eigenvalues().minCoeff(), 0);
    const double volume = tet10_volume_m3(x);
    const Eigen::Matrix<double, kTet10Dofs, 6> r = rigid_motions(x);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.col(c).dot(m * r.col(c)), kRhoKgM3 * volume, 1e-13 * kRhoKgM3 * volume);
  }
  const Eigen::Matrix3d straight = generic_tet().leftCols<3>().colwise() - generic_tet().col(3);
  EXPECT_NEAR(tet10_volume_m3(generic_tet()), std::abs(straight.determinant()) / 6, 1e-18);
}

TEST(Tet10Mass, StraightElementMatchesTheBarycentricIntegrals) {
  // integral of L0^a L1^b L2^c L3^d = a! b! c! d! 3! V / (a + b + c + d + 3)!, with N written in
  // the barycentric coordinates L: vertex 2 L^2 - L, mid-node 4 L_a L_b.
  using Poly = std::map<std::array<int, 4>, double>;
  auto shape = [](int i) {
    Poly p;
    if (i < 4) {
      std::array<int, 4> sq{}, lin{};
      sq[i] = 2;
      lin[i] = 1;
      p[sq] = 2;
      p[lin] = -1;
    } else {
      std::array<int, 4> e{};
      e[kTet10Edges[i - 4][0]] = e[kTet10Edges[i - 4][1]] = 1;
      p[e] = 4;
    }
    return p;
  };
  const Tet10Coords x = generic_tet();
  const double volume = tet10_volume_m3(x);
  const Tet10Matrix m = tet10_mass(x, kRhoKgM3);
  for (int i = 0; i < kTet10Nodes; ++i)
    for (int j = 0; j < kTet10Nodes; ++j) {
      double integral = 0;
      for (const auto& [ea, ca] : shape(i))
        for (const auto& [eb, cb] : shape(j)) {
          double term = 6 * volume * ca * cb;
          int sum = 0;
          for (int d = 0; d < 4; ++d) {
            term *= factorial(ea[d] + eb[d]);
            sum += ea[d] + eb[d];
          }
          integral += term / factorial(sum + 3);
        }
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(m(3 * i + c, 3 * j + c), kRhoKgM3 * integral, 1e-14 * kRhoKgM3 * volume);
    }
}

namespace {

// The box [0, l0] x [0, l1] x [0, l2] as 6 tetrahedra around its main diagonal (Kuhn's split), mid-nodes
// at the edge midpoints and shared between elements.
Tet10Mesh box_mesh(const Eigen::Vector3d& l) {
  Tet10Mesh mesh;
  std::vector<Eigen::Vector3d> nodes;
  for (int corner = 0; corner < 8; ++corner)
    nodes.emplace_back((corner & 1) * l(0), ((corner >> 1) & 1) * l(1), ((corner >> 2) & 1) * l(2));
  std::map<std::pair<int, int>, int> mid;
  const std::array<std::array<int, 3>, 6> orders = {{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (const auto& order : orders) {
    std::array<int, 4> v = {0, 1 << order[0], (1 << order[0]) | (1 << order[1]), 7};
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k) edges.col(k) = nodes[v[k + 1]] - nodes[v[0]];
    if (edges.determinant() < 0) std::swap(v[1], v[2]);
    std::array<int, kTet10Nodes> element{};
    for (int i = 0; i < 4; ++i) element[i] = v[i];
    for (int e = 0; e < 6; ++e) {
      const int a = v[kTet10Edges[e][0]], b = v[kTet10Edges[e][1]];
      const auto key = std::minmax(a, b);
      auto [it, fresh] = mid.emplace(key, static_cast<int>(nodes.size()));
      if (fresh) nodes.emplace_back(0.5 * (nodes[a] + nodes[b]));
      element[4 + e] = it->second;
    }
    mesh.elements.push_back(element);
  }
  mesh.nodes_m.resize(3, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t i = 0; i < nodes.size(); ++i) mesh.nodes_m.col(static_cast<Eigen::Index>(i)) = nodes[i];
  return mesh;
}

// Strain energy density (J/m^3) of the symmetric strain e.
// Lamé constants from their definitions, not from the material's accessors.
double energy_density(const Eigen::Matrix3d& e, const clatter::model::Material& m) {
  const double mu_pa = m.youngs_pa / (2 * (1 + m.poisson));
  const double lambda_pa = m.youngs_pa * m.poisson / ((1 + m.poisson) * (1 - 2 * m.poisson));
  return 0.5 * lambda_pa * e.trace() * e.trace() + mu_pa * (e.array() * e.array()).sum();
}

// A displacement u_i(x) = g(i, :) x + x^T h[i] x / 2 (linear when every h[i] is zero), metres.
struct Field {
  Eigen::Matrix3d g;
  std::array<Eigen::Matrix3d, 3> h;  // h[i](j, k) = d^2 u_i / dx_j dx_k
  Eigen::Vector3d at(const Eigen::Vector3d& x) const {
    Eigen::Vector3d u = g * x;
    for (int i = 0; i < 3; ++i) u(i) += 0.5 * x.dot(h[i] * x);
    return u;
  }
  Eigen::Matrix3d strain(const Eigen::Vector3d& x) const {
    Eigen::Matrix3d grad = g;
    for (int i = 0; i < 3; ++i) grad.row(i) += (h[i] * x).transpose();
    return 0.5 * (grad + grad.transpose());
  }
};

Field make_field(bool quadratic) {
  Field f;
  f.g << 1.0, 0.3, -0.2, 0.5, -0.7, 0.4, 0.1, 0.6, 0.9;
  f.g *= 1e-3;
  for (int i = 0; i < 3; ++i) {
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    if (quadratic) a << 1.0 + i, 0.2, -0.3 * i, 0.4, -0.5, 0.6, 0.7 * i, -0.8, 0.9;
    f.h[i] = 0.02 * (a + a.transpose());
  }
  return f;
}

// The exact strain energy of f over the box: the density is a quadratic, so 3-point Gauss-Legendre
// per axis is exact.
double exact_energy(const Field& f, const Eigen::Vector3d& l, const clatter::model::Material& m) {
  std::vector<double> x, w;
  gauss_legendre_unit(3, x, w);
  double e = 0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      for (std::size_t k = 0; k < 3; ++k)
        e += w[i] * w[j] * w[k] * energy_density(f.strain(Eigen::Vector3d(x[i] * l(0), x[j] * l(1), x[k] * l(2))), m);
  return e * l.prod();
}

}  // namespace

TEST(Tet10Patch, LinearAndQuadraticFieldsHaveTheExactStrainEnergy) {
  const Eigen::Vector3d box(0.2, 0.3, 0.5);
  const Tet10Mesh mesh = box_mesh(box);
  ASSERT_EQ(mesh.nodes_m.cols(), 8 + 19);  // 12 box edges, 6 face diagonals, 1 main diagonal
  const Eigen::SparseMatrix<double> k = assemble_stiffness(mesh, kSteel);
  for (bool quadratic : {false, true}) {
    const Field f = make_field(quadratic);
    Eigen::VectorXd u(3 * mesh.nodes_m.cols());
    for (Eigen::Index n = 0; n < mesh.nodes_m.cols(); ++n) u.segment<3>(3 * n) = f.at(mesh.nodes_m.col(n));
    const double want = exact_energy(f, box, kSteel);
    EXPECT_NEAR(0.5 * u.dot(k * u), want, 1e-12 * want) << (quadratic ? "quadratic" : "linear");
    if (!quadratic) {
      // No body force: the interior node (the middle of the main diagonal) feels no net force.
      const Eigen::VectorXd force = k * u;
      Eigen::Index centre = 0;
      (mesh.nodes_m.colwise() - 0.5 * box).colwise().norm().minCoeff(&centre);
      ASSERT_LT((mesh.nodes_m.col(centre) - 0.5 * box).norm(), 1e-15);
      EXPECT_LT(force.segment<3>(3 * centre).norm(), 1e-10 * force.norm());
    }
  }
  const Eigen::SparseMatrix<double> m = assemble_mass(mesh, kRhoKgM3);
  Eigen::VectorXd ones = Eigen::VectorXd::Zero(3 * mesh.nodes_m.cols());
  for (Eigen::Index n = 0; n < mesh.nodes_m.cols(); ++n) ones(3 * n + 1) = 1;
  EXPECT_NEAR(ones.dot(m * ones), kRhoKgM3 * box.prod(), 1e-13 * kRhoKgM3 * box.prod());
}

namespace {

// The volume of a (curved) element from its boundary alone: V = (1/3) sum over the faces of the
// integral of x . (x_s x x_t) ds dt, each face a 6-node quadratic triangle; the integrand is a
// polynomial of degree 4, integrated exactly by a collapsed 2D Gauss rule.
double volume_from_faces(const Tet10Coords& x) {
  auto mid_node = [](int a, int b) {
    for (int e = 0; e < 6; ++e)
      if (std::minmax(a, b) == std::minmax(kTet10Edges[e][0], kTet10Edges[e][1])) return 4 + e;
    return -1;
  };
  const std::array<std::array<int, 3>, 4> faces = {{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}};  // outward
  std::vector<double> g, w;
  gauss_legendre_unit(5, g, w);
  double v = 0;
  for (const auto& f : faces) {
    const std::array<int, 6> n = {f[0], f[1], f[2], mid_node(f[0], f[1]), mid_node(f[1], f[2]), mid_node(f[2], f[0])};
    for (std::size_t i = 0; i < g.size(); ++i)
      for (std::size_t j = 0; j < g.size(); ++j) {
        const double s = g[i], t = g[j] * (1 - g[i]), l = 1 - s - t;
        // P2 triangle on (l, s, t): vertices L(2L - 1), mid-nodes 4 L_a L_b.
        const std::array<double, 6> shape = {l * (2 * l - 1), s * (2 * s - 1), t * (2 * t - 1),
                                             4 * l * s,       4 * s * t,       4 * t * l};
        const std::array<double, 6> ds = {1 - 4 * l, 4 * s - 1, 0, 4 * (l - s), 4 * t, -4 * t};
        const std::array<double, 6> dt = {1 - 4 * l, 0, 4 * t - 1, -4 * s, 4 * s, 4 * (l - t)};
        Eigen::Vector3d p = Eigen::Vector3d::Zero(), ps = p, pt = p;
        for (int a = 0; a < 6; ++a) {
          p += shape[a] * x.col(n[a]);
          ps += ds[a] * x.col(n[a]);
          pt += dt[a] * x.col(n[a]);
        }
        v += w[i] * w[j] * (1 - g[i]) * p.dot(ps.cross(pt)) / 3;
      }
  }
  return v;
}

}  // namespace

TEST(Tet10Curved, QuadratureGivesTheExactVolumeOfACurvedElement) {
  const Tet10Coords straight = generic_tet(), curved = curved_tet();
  EXPECT_NEAR(volume_from_faces(straight), tet10_volume_m3(straight), 1e-17);
  const double want = volume_from_faces(curved);
  ASSERT_GT(std::abs(want - tet10_volume_m3(straight)), 0.05 * want);  // the mid-node moved noticeably
  // det J is a cubic for a quadratic map: the degree-5 rule is exact.
  EXPECT_NEAR(tet10_volume_m3(curved), want, 1e-14 * want);
  EXPECT_NEAR(tet10_volume_m3(curved, collapsed_gauss(3)), want, 1e-14 * want);
  const Tet10Matrix m = tet10_mass(curved, kRhoKgM3);
  const Eigen::Matrix<double, kTet10Dofs, 6> r = rigid_motions(curved);
  EXPECT_NEAR(r.col(0).dot(m * r.col(0)), kRhoKgM3 * want, 1e-13 * kRhoKgM3 * want);
}

TEST(Tet10Curved, StiffnessOfACurvedElementConvergesWithTheRule) {
  // The integrand is rational on a curved element: the default degree-5 rule against a degree-14
  // one differs by 3e-5 (relative, Frobenius) for this curvature (the volume grows 22%); on a
  // straight element the degree-2 rule is already exact.
  const Tet10Coords x = curved_tet();
  const Tet10Matrix fine = tet10_stiffness(x, kSteel, collapsed_gauss(14));
  const double error = (tet10_stiffness(x, kSteel) - fine).norm() / fine.norm();
  EXPECT_LT(error, 1e-4);
  const Tet10Matrix straight = tet10_stiffness(generic_tet(), kSteel, collapsed_gauss(14));
  EXPECT_LT((tet10_stiffness(generic_tet(), kSteel, keast_degree2()) - straight).norm(), 1e-13 * straight.norm());
}

TEST(Tet10Curved, AnInvertedElementIsReported) {
  Tet10Coords mirrored = generic_tet();
  mirrored.row(0) *= -1;  // a reflection turns the orientation inside out
  EXPECT_THROW(tet10_stiffness(mirrored, kSteel), InvertedElement);
  EXPECT_THROW(tet10_mass(mirrored, kRhoKgM3), InvertedElement);
  // A mid-node dragged past the opposite face folds the element near it.
  Tet10Coords folded = generic_tet();
  folded.col(4) = folded.col(2) + 0.3 * (folded.col(2) - folded.col(4));
  try {
    tet10_volume_m3(folded);
    FAIL() << "a folded element was integrated";
  } catch (const InvertedElement& e) {
    EXPECT_LE(e.det_jacobian_m3, 0);
    EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos);
  }
}
