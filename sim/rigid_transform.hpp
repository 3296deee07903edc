#pragma once
// A rigid placement x -> R x + t, R a unit quaternion: how clatter-sim moves between a mesh's own
// coordinates, a body's principal frame and the world.
#include <array>
#include <cmath>

#include "core/rotation.hpp"

namespace clatter::sim {

inline Quaternion multiply(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// The rotation whose matrix has columns c[.][j] (a right-handed orthonormal frame), w >= 0.
inline Quaternion quaternion_from_columns(const std::array<std::array<double, 3>, 3>& m) {
  // Shepperd's method: divide by the largest of the four candidate components.
  const double tr = m[0][0] + m[1][1] + m[2][2];
  Quaternion q;
  if (tr >= m[0][0] && tr >= m[1][1] && tr >= m[2][2]) {
    const double s = 2 * std::sqrt(1 + tr);
    q = {s / 4, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
  } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
    const double s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
    q = {(m[2][1] - m[1][2]) / s, s / 4, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
  } else if (m[1][1] >= m[2][2]) {
    const double s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);
    q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, s / 4, (m[1][2] + m[2][1]) / s};
  } else {
    const double s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
    q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / 4};
  }
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) * (q[0] < 0 ? -1 : 1);
  for (double& x : q) x /= n;
  return q;
}

struct RigidTransform {
  Quaternion rotation{1, 0, 0, 0};
  Vec3 translation_m{};

  Vec3 apply(const Vec3& x) const {
    const Vec3 r = rotate(rotation, x);
    return {r[0] + translation_m[0], r[1] + translation_m[1], r[2] + translation_m[2]};
  }
  // (this o other)(x) = this(other(x))
  RigidTransform compose(const RigidTransform& other) const { return {multiply(rotation, other.rotation), apply(other.translation_m)}; }
  RigidTransform inverse() const {
    const Quaternion q{rotation[0], -rotation[1], -rotation[2], -rotation[3]};
    const Vec3 t = rotate(q, translation_m);
    return {q, {-t[0], -t[1], -t[2]}};
  }
};

}  // namespace clatter::sim
