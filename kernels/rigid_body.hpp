#pragma once
// A rigid piece of debris as its PAN proxy (Chadwick et al. 2012, section 3.3, eq. 11): the
// ellipsoid with the piece's principal moments of inertia (shape) and volume (size).
#include <array>

#include "core/vec3.hpp"

namespace clatter::kernels {

using Mat3 = std::array<std::array<double, 3>, 3>;

struct ProxyFit {
  // Semi-axes a >= b >= c [m] of the equivalent ellipsoid.
  double a_m = 0, b_m = 0, c_m = 0;
  // Columns: the body-frame unit vectors of the proxy's x, y, z axes (the principal axes of the
  // smallest, middle and largest moment; a right-handed frame).
  Mat3 axes{};
  Vec3 moments_kg_m2{};  // principal moments about those axes (ascending)
};

// Throws std::invalid_argument unless the inertia is symmetric positive definite and physically
// possible for a rigid body (each principal moment at most the sum of the other two), mass > 0,
// volume > 0. For a solid ellipsoid, eq. (11): I_x = m (b^2 + c^2) / 5 etc., so
// a^2 = 5 (I_y + I_z - I_x) / (2 m); the three are then scaled together to the given volume.
ProxyFit fit_proxy(const Mat3& inertia_kg_m2, double mass_kg, double volume_m3);

// The surface area of the ellipsoid with semi-axes a, b, c (any order, all > 0), exactly
// (Legendre): for a >= b >= c, phi = acos(c / a), k^2 = a^2 (b^2 - c^2) / (b^2 (a^2 - c^2)),
//   S = 2 pi c^2 + (2 pi a b / sin phi) (E(phi, k) sin^2 phi + F(phi, k) cos^2 phi),
// with the incomplete elliptic integrals of GSL; 4 pi a^2 for a sphere.
double ellipsoid_surface_area_m2(double a_m, double b_m, double c_m);

Vec3 to_proxy_frame(const ProxyFit& fit, const Vec3& body);  // components along the proxy axes

}  // namespace clatter::kernels
