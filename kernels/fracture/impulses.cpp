#include "kernels/fracture/impulses.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <map>
#include <stdexcept>

namespace clatter::kernels::fracture {
namespace {

Eigen::Matrix3d eig(const Mat3& m) {
  Eigen::Matrix3d e;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) e(i, j) = m[i][j];
  return e;
}
Eigen::Vector3d eig(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 vec(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

}  // namespace

FractureImpulses fracture_impulses(const std::vector<FractureTriangle>& faces, const std::vector<Mat3>& stress_pa,
                                   const std::vector<PieceInertia>& pieces, const std::vector<Vec3>& v_m_s,
                                   const std::vector<Vec3>& w_rad_s, double released_j) {
  const std::size_t n = pieces.size();
  if (v_m_s.size() != n || w_rad_s.size() != n) throw std::invalid_argument("fracture_impulses: one velocity per piece");
  std::vector<Eigen::Vector3d> force(n, Eigen::Vector3d::Zero()), torque(n, Eigen::Vector3d::Zero());
  struct Side {
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();  // moment: area-weighted centroid
    double area = 0;
  };
  std::map<std::pair<int, int>, Side> sides;
  for (const FractureTriangle& f : faces) {
    if (f.piece < 0 || static_cast<std::size_t>(f.piece) >= n || f.tet < 0 || static_cast<std::size_t>(f.tet) >= stress_pa.size())
      throw std::invalid_argument("fracture_impulses: a face names a piece or tetrahedron that does not exist");
    const Eigen::Vector3d a = eig(f.points_m[0]), b = eig(f.points_m[1]), c = eig(f.points_m[2]);
    const Eigen::Vector3d area_normal = (b - a).cross(c - a) / 2;  // a_i n_i, outward from the piece
    const Eigen::Vector3d s = -eig(stress_pa[f.tet]) * area_normal;
    const Eigen::Vector3d centroid = (a + b + c) / 3;
    force[f.piece] += s;
    torque[f.piece] += (centroid - eig(pieces[f.piece].centre_m)).cross(s);
    Side& side = sides[{f.piece, f.other}];
    side.force += s;
    side.area += area_normal.norm();
    side.moment += area_normal.norm() * centroid;
  }
  // Delta E_K(tau) = A tau^2 + B tau with A = 1/2 sum (|S|^2/m + J^T I^-1 J), B = sum (v.S + w.J).
  std::vector<Eigen::Vector3d> inv_i_j(n);
  double quad = 0, lin = 0;
  for (std::size_t d = 0; d < n; ++d) {
    inv_i_j[d] = eig(pieces[d].inertia_kg_m2).ldlt().solve(torque[d]);
    quad += 0.5 * (force[d].squaredNorm() / pieces[d].mass_kg + torque[d].dot(inv_i_j[d]));
    lin += eig(v_m_s[d]).dot(force[d]) + eig(w_rad_s[d]).dot(torque[d]);
  }
  FractureImpulses out;
  out.dv_m_s.assign(n, Vec3{}), out.dw_rad_s.assign(n, Vec3{});
  for (std::size_t d = 0; d < n; ++d) out.force_n.push_back(vec(force[d])), out.torque_nm.push_back(vec(torque[d]));
  if (released_j > 0 && quad > 0)  // the one positive root of A tau^2 + B tau - released = 0 (A > 0)
    out.tau_s = 2 * released_j / (lin + std::sqrt(lin * lin + 4 * quad * released_j));
  for (std::size_t d = 0; d < n; ++d) {
    out.dv_m_s[d] = vec(out.tau_s / pieces[d].mass_kg * force[d]);
    out.dw_rad_s[d] = vec(out.tau_s * inv_i_j[d]);
    const Eigen::Vector3d v0 = eig(v_m_s[d]), w0 = eig(w_rad_s[d]);
    const Eigen::Vector3d v1 = v0 + eig(out.dv_m_s[d]), w1 = w0 + eig(out.dw_rad_s[d]);
    const Eigen::Matrix3d inertia = eig(pieces[d].inertia_kg_m2);
    out.kinetic_energy_gained_j +=
        0.5 * pieces[d].mass_kg * (v1.squaredNorm() - v0.squaredNorm()) + 0.5 * (w1.dot(inertia * w1) - w0.dot(inertia * w0));
  }
  for (const auto& [key, side] : sides)
    if (side.area > 0) out.interfaces.push_back({key.first, key.second, vec(side.moment / side.area), vec(out.tau_s * side.force), side.area});
  return out;
}

}  // namespace clatter::kernels::fracture
