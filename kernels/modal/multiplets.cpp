#include "kernels/modal/multiplets.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace clatter::kernels::modal {
namespace {

// Dunavant's 6-point rule, exact to degree 4 on a triangle: barycentric points, weights summing to 1.
constexpr double kA = 0.445948490915965, kWa = 0.223381589678011;
constexpr double kB = 0.091576213509771, kWb = 0.109951743655322;
constexpr std::array<std::array<double, 3>, 6> kPoints{{{kA, kA, 1 - 2 * kA},
                                                        {kA, 1 - 2 * kA, kA},
                                                        {1 - 2 * kA, kA, kA},
                                                        {kB, kB, 1 - 2 * kB},
                                                        {kB, 1 - 2 * kB, kB},
                                                        {1 - 2 * kB, kB, kB}}};
constexpr std::array<double, 6> kWeights{kWa, kWa, kWa, kWb, kWb, kWb};

// One quadrature point of the surface: its weight (area), the 6 nodes' shape functions, and per
// generator the nodal weights of the derivative along e x x.
struct SurfacePoint {
  std::array<std::int32_t, 6> nodes{};
  double area_m2 = 0;
  std::array<double, 6> value{};
  std::vector<std::array<double, 6>> along;  // per generator axis
};

std::vector<SurfacePoint> surface_points(std::span<const std::array<double, 3>> nodes_m,
                                         std::span<const std::array<std::int32_t, 6>> faces, std::span<const int> axes) {
  std::vector<SurfacePoint> out;
  out.reserve(faces.size() * kPoints.size());
  for (const auto& face : faces) {
    for (std::size_t q = 0; q < kPoints.size(); ++q) {
      const double l0 = kPoints[q][0], l1 = kPoints[q][1], l2 = kPoints[q][2];
      // Barycentric (l0, l1, l2) with xi = l1, eta = l2.
      const std::array<double, 6> n{l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1),
                                    4 * l0 * l1,       4 * l1 * l2,       4 * l2 * l0};
      const std::array<double, 6> d_xi{-(4 * l0 - 1), 4 * l1 - 1, 0, 4 * (l0 - l1), 4 * l2, -4 * l2};
      const std::array<double, 6> d_eta{-(4 * l0 - 1), 0, 4 * l2 - 1, -4 * l1, 4 * l1, 4 * (l0 - l2)};
      Eigen::Vector3d x = Eigen::Vector3d::Zero(), x_xi = Eigen::Vector3d::Zero(), x_eta = Eigen::Vector3d::Zero();
      for (std::size_t k = 0; k < 6; ++k) {
        const auto& p = nodes_m[static_cast<std::size_t>(face[k])];
        const Eigen::Vector3d v(p[0], p[1], p[2]);
        x += n[k] * v;
        x_xi += d_xi[k] * v;
        x_eta += d_eta[k] * v;
      }
      SurfacePoint s;
      s.nodes = face;
      s.value = n;
      s.area_m2 = 0.5 * kWeights[q] * x_xi.cross(x_eta).norm();
      Eigen::Matrix<double, 3, 2> t;
      t << x_xi, x_eta;
      const Eigen::Matrix2d metric = t.transpose() * t;
      for (int axis : axes) {
        // e x x is tangent to a surface of revolution about e; its components in (x_xi, x_eta).
        const Eigen::Vector2d c = metric.ldlt().solve(t.transpose() * Eigen::Vector3d::Unit(axis).cross(x));
        std::array<double, 6> w{};
        for (std::size_t k = 0; k < 6; ++k) w[k] = c(0) * d_xi[k] + c(1) * d_eta[k];
        s.along.push_back(w);
      }
      out.push_back(std::move(s));
    }
  }
  return out;
}

// sum_e (J_e U)^T W (J_e U) of one cluster [begin, end), in the coordinates where G = U^T W U is
// the identity (L^-1 . L^-T, G = L L^T), and L^T (the modes' coordinates there are its columns).
// For a J-invariant span this is -sum_e A_e^2; for a span that is not (one member of a doublet) it
// still gives each pure mode its m^2 or n (n + 1), where the compression to the span would give 0.
struct ClusterOperators {
  Eigen::MatrixXd casimir;
  Eigen::MatrixXd lt;  // L^T
};

ClusterOperators cluster_operators(const std::vector<SurfacePoint>& points, std::span<const double> shapes,
                                   std::size_t nodes, int begin, int end, std::span<const int> axes) {
  const auto k = static_cast<Eigen::Index>(end - begin);
  const auto n_axes = static_cast<std::size_t>(axes.size());
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(k, k), t = Eigen::MatrixXd::Zero(k, k);
  Eigen::Matrix3Xd u(3, k);
  std::vector<Eigen::Matrix3Xd> ju(n_axes, Eigen::Matrix3Xd(3, k));
  for (const auto& p : points) {
    u.setZero();
    for (auto& j : ju) j.setZero();
    for (Eigen::Index i = 0; i < k; ++i) {
      const double* mode = shapes.data() + static_cast<std::size_t>(begin + i) * nodes * 3;
      for (std::size_t a = 0; a < 6; ++a) {
        const Eigen::Map<const Eigen::Vector3d> v(mode + 3 * static_cast<std::size_t>(p.nodes[a]));
        u.col(i) += p.value[a] * v;
        for (std::size_t e = 0; e < n_axes; ++e) ju[e].col(i) -= p.along[e][a] * v;
      }
      for (std::size_t e = 0; e < n_axes; ++e) ju[e].col(i) += Eigen::Vector3d::Unit(axes[e]).cross(u.col(i));
    }
    g.noalias() += p.area_m2 * u.transpose() * u;
    for (std::size_t e = 0; e < n_axes; ++e) t.noalias() += p.area_m2 * ju[e].transpose() * ju[e];
  }
  g = 0.5 * (g + g.transpose()).eval();
  const Eigen::LLT<Eigen::MatrixXd> llt(g);
  if (llt.info() != Eigen::Success) throw std::invalid_argument("find_multiplets: surface shapes linearly dependent");
  const Eigen::MatrixXd l = llt.matrixL();
  const Eigen::MatrixXd left = l.triangularView<Eigen::Lower>().solve(t);
  Eigen::MatrixXd c = l.triangularView<Eigen::Lower>().solve(left.transpose()).transpose();
  return {0.5 * (c + c.transpose()), l.transpose()};
}

// The order an eigenvalue of the Casimir stands for: |m| from m^2, n from n (n + 1).
double order_of(double eigenvalue, SymmetryKind kind) {
  const double c = std::max(0.0, eigenvalue);
  return kind == SymmetryKind::sphere ? 0.5 * (std::sqrt(1 + 4 * c) - 1) : std::sqrt(c);
}

int members(int order, SymmetryKind kind) {
  if (kind == SymmetryKind::sphere) return 2 * order + 1;
  return order == 0 ? 1 : 2;
}

}  // namespace

EllipsoidSymmetry ellipsoid_symmetry(const std::array<double, 3>& r, double tolerance) {
  auto equal = [&](double p, double q) { return std::abs(p - q) <= tolerance * std::max(std::abs(p), std::abs(q)); };
  const bool xy = equal(r[0], r[1]), yz = equal(r[1], r[2]), xz = equal(r[0], r[2]);
  if (xy && yz) return {SymmetryKind::sphere, -1};
  if (xy) return {SymmetryKind::spheroid, 2};
  if (yz) return {SymmetryKind::spheroid, 0};
  if (xz) return {SymmetryKind::spheroid, 1};
  return {};
}

Multiplets find_multiplets(std::span<const std::array<double, 3>> nodes_m,
                           std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shapes,
                           std::span<const std::int32_t> cluster, const EllipsoidSymmetry& symmetry) {
  const std::size_t n_modes = cluster.size(), n_nodes = nodes_m.size();
  if (shapes.size() != n_modes * n_nodes * 3) throw std::invalid_argument("find_multiplets: shapes are not [mode][node][3]");
  for (const auto& f : faces)
    for (auto v : f)
      if (v < 0 || static_cast<std::size_t>(v) >= n_nodes) throw std::invalid_argument("find_multiplets: face node out of range");
  Multiplets out;
  out.multiplet.assign(n_modes, -1);
  out.order.assign(n_modes, -1);
  if (symmetry.kind == SymmetryKind::none) {
    for (std::size_t i = 0; i < n_modes; ++i) out.multiplet[i] = static_cast<std::int32_t>(i);
    return out;
  }
  const std::vector<int> axes = symmetry.kind == SymmetryKind::sphere ? std::vector<int>{0, 1, 2} : std::vector<int>{symmetry.axis};
  const auto points = surface_points(nodes_m, faces, axes);
  // (lowest member, members) of every multiplet, numbered once all clusters are done.
  std::vector<std::vector<int>> groups;
  for (std::size_t begin = 0; begin < n_modes;) {
    std::size_t end = begin + 1;
    while (end < n_modes && cluster[end] == cluster[begin]) ++end;
    const int b = static_cast<int>(begin), e = static_cast<int>(end), k = e - b;
    const auto ops = cluster_operators(points, shapes, n_nodes, b, e, axes);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(ops.casimir);
    // Each eigenvector's integer order; the dimension of each order's eigenspace.
    std::vector<int> vector_order(static_cast<std::size_t>(k));
    std::map<int, int> capacity;
    for (int j = 0; j < k; ++j) {
      const double o = order_of(eig.eigenvalues()(j), symmetry.kind);
      const int rounded = static_cast<int>(std::lround(o));
      out.order_defect = std::max(out.order_defect, std::abs(o - rounded));
      vector_order[static_cast<std::size_t>(j)] = rounded;
      ++capacity[rounded];
    }
    // Mode i's weight in each order: the squared projections of its (G-whitened) coordinates.
    std::vector<std::tuple<double, int, int>> weights;  // (-weight, mode, order): sorted, best first
    for (int i = 0; i < k; ++i) {
      const Eigen::VectorXd z = ops.lt.col(i);
      const Eigen::VectorXd projection = eig.eigenvectors().transpose() * z;
      std::map<int, double> w;
      for (int j = 0; j < k; ++j) w[vector_order[static_cast<std::size_t>(j)]] += projection(j) * projection(j) / z.squaredNorm();
      for (const auto& [o, x] : w) weights.emplace_back(-x, i, o);
    }
    std::sort(weights.begin(), weights.end());
    std::vector<int> assigned(static_cast<std::size_t>(k), -1);
    for (const auto& [w, i, o] : weights)
      if (assigned[static_cast<std::size_t>(i)] < 0 && capacity[o] > 0) {
        assigned[static_cast<std::size_t>(i)] = o;
        --capacity[o];
      }
    // Per order, members in frequency (= mode) order, grouped by the multiplet size.
    std::map<int, std::vector<int>> by_order;
    for (int i = 0; i < k; ++i) by_order[assigned[static_cast<std::size_t>(i)]].push_back(b + i);
    for (const auto& [o, modes] : by_order) {
      const auto size = static_cast<std::size_t>(members(o, symmetry.kind));
      for (std::size_t at = 0; at < modes.size(); at += size) {
        groups.emplace_back(modes.begin() + static_cast<long>(at),
                            modes.begin() + static_cast<long>(std::min(modes.size(), at + size)));
        if (groups.back().size() < size) ++out.incomplete;
        for (int m : groups.back()) out.order[static_cast<std::size_t>(m)] = o;
      }
    }
    begin = end;
  }
  std::sort(groups.begin(), groups.end());  // by lowest member: the numbering follows frequency
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (int m : groups[g]) out.multiplet[static_cast<std::size_t>(m)] = static_cast<std::int32_t>(g);
  return out;
}

}  // namespace clatter::kernels::modal
