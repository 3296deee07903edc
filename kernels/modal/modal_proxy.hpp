#pragma once
// A rigid piece as its modal soundbank proxy (003 section 5.2): the normalized ellipsoid of its
// principal moments (eq. 12), the rotation R = V_I^T from its body frame into the proxy's frame,
// and the contact point on the proxy where a force acts (Appendix F).
#include <array>

#include "core/vec3.hpp"
#include "kernels/rigid_body.hpp"

namespace clatter::kernels::modal {

struct ModalProxyFrame {
  // Eq. (12): semi-axes a <= b <= c with a^2 + b^2 + c^2 = 1, from the principal moments
  // I_1 >= I_2 >= I_3 (a^2 proportional to -I_1 + I_2 + I_3, the axis of the largest moment).
  std::array<double, 3> unit_axes{};
  // Rows: the body-frame unit vectors of the proxy's x (largest moment), y and z (smallest)
  // axes, a proper rotation: proxy = rotation * body.
  Mat3 rotation{};
};

// From the PAN proxy fit of the same inertia (kernels/rigid_body.hpp: a >= b >= c, axes by
// ascending moment), whose axis ratios are eq. (12)'s: the order is reversed.
ModalProxyFrame modal_proxy_frame(const ProxyFit& fit);

Vec3 to_modal_frame(const ModalProxyFrame& frame, const Vec3& body);

// Appendix F: the point of the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 whose outward normal is
// the unit vector n (for a force f: n = -f / |f|). Eq. (23)'s solution in closed form: grad g is
// parallel to n where x_i = a_i^2 n_i / sqrt(sum_j a_j^2 n_j^2), which also lies on the surface;
// unlike (23) it stays regular when n is along an axis.
Vec3 contact_point(const std::array<double, 3>& axes_m, const Vec3& outward_normal);

}  // namespace clatter::kernels::modal
