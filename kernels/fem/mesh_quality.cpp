#include "kernels/fem/mesh_quality.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>


namespace clatter::kernels::fem {
namespace {

using Vertices = Eigen::Matrix<double, 3, 4>;

// Circumradius over the shortest edge (sqrt(6)/4 = 0.612 for the regular tetrahedron).
double radius_edge(const Vertices& v) {
  Eigen::Matrix3d a;
  Eigen::Vector3d rhs;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d d = v.col(k + 1) - v.col(0);
    a.row(k) = d.transpose();
    rhs(k) = 0.5 * d.squaredNorm();
  }
  const double radius = a.fullPivLu().solve(rhs).norm();
  double shortest = std::numeric_limits<double>::infinity();
  for (const auto& e : kTet10Edges) shortest = std::min(shortest, (v.col(e[0]) - v.col(e[1])).norm());
  return radius / shortest;
}

// The six dihedral angles (degrees): at edge ij, the angle between the perpendiculars dropped
// from the two other vertices onto the edge's line.
std::array<double, 6> dihedral_deg(const Vertices& v) {
  std::array<double, 6> out{};
  for (int e = 0; e < 6; ++e) {
    const int i = kTet10Edges[e][0], j = kTet10Edges[e][1];
    int others[2], n = 0;
    for (int k = 0; k < 4; ++k)
      if (k != i && k != j) others[n++] = k;
    const Eigen::Vector3d axis = (v.col(j) - v.col(i)).normalized();
    Eigen::Vector3d p[2];
    for (int s = 0; s < 2; ++s) {
      const Eigen::Vector3d d = v.col(others[s]) - v.col(i);
      p[s] = d - d.dot(axis) * axis;
    }
    const double c = std::clamp(p[0].normalized().dot(p[1].normalized()), -1.0, 1.0);
    out[e] = std::acos(c) * 180 / std::numbers::pi;
  }
  return out;
}

}  // namespace

double jacobian_ratio(const Tet10Coords& x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto sample = [&](const RefPoint& p) {
    const double det = tet10_jacobian(x, p).determinant();
    lo = std::min(lo, det);
    hi = std::max(hi, det);
  };
  for (int i = 0; i < kTet10Nodes; ++i) sample(tet10_reference_node(i));
  for (const auto& p : keast_degree5().points) sample(p);
  return hi > 0 ? lo / hi : -1;
}

ElementQuality element_quality(const Tet10Coords& x) {
  const Vertices v = x.leftCols<4>();
  ElementQuality q;
  q.radius_edge = radius_edge(v);
  q.min_dihedral_deg = 180;
  for (double angle : dihedral_deg(v)) {
    q.min_dihedral_deg = std::min(q.min_dihedral_deg, angle);
    q.max_dihedral_deg = std::max(q.max_dihedral_deg, angle);
  }
  q.jacobian_ratio = jacobian_ratio(x);
  return q;
}

MeshQuality mesh_quality(const Tet10Mesh& mesh) {
  MeshQuality q;
  q.elements = static_cast<long long>(mesh.elements.size());
  q.nodes = mesh.nodes_m.cols();
  q.dofs = 3 * q.nodes;
  q.min_dihedral_deg = 180;
  q.min_jacobian_ratio = std::numeric_limits<double>::infinity();
  double sum_radius_edge = 0;
  for (const auto& e : mesh.elements) {
    Tet10Coords x;
    for (int i = 0; i < kTet10Nodes; ++i) x.col(i) = mesh.nodes_m.col(e[i]);
    const ElementQuality eq = element_quality(x);
    q.max_radius_edge = std::max(q.max_radius_edge, eq.radius_edge);
    sum_radius_edge += eq.radius_edge;
    q.min_dihedral_deg = std::min(q.min_dihedral_deg, eq.min_dihedral_deg);
    q.max_dihedral_deg = std::max(q.max_dihedral_deg, eq.max_dihedral_deg);
    q.min_jacobian_ratio = std::min(q.min_jacobian_ratio, eq.jacobian_ratio);
  }
  if (q.elements > 0) q.mean_radius_edge = sum_radius_edge / static_cast<double>(q.elements);
  return q;
}

}  // namespace clatter::kernels::fem
