#pragma once
// Rotations by a unit quaternion (w, x, y, z), shared by the scene readers and the synthesizer.
#include <array>

#include "core/vec3.hpp"

namespace clatter {

using Quaternion = std::array<double, 4>;  // w, x, y, z

// v' = v + 2w (u x v) + 2 u x (u x v), u = (x, y, z).
inline Vec3 rotate(const Quaternion& q, const Vec3& v) {
  const Vec3 u{q[1], q[2], q[3]};
  const Vec3 t = cross(u, v), t2 = cross(u, t);
  return {v[0] + 2 * (q[0] * t[0] + t2[0]), v[1] + 2 * (q[0] * t[1] + t2[1]), v[2] + 2 * (q[0] * t[2] + t2[2])};
}

inline Vec3 rotate_inverse(const Quaternion& q, const Vec3& v) { return rotate({q[0], -q[1], -q[2], -q[3]}, v); }

}  // namespace clatter
