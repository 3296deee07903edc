#include "kernels/modal/modal_proxy.hpp"

#include <cmath>

namespace clatter::kernels::modal {

ModalProxyFrame modal_proxy_frame(const ProxyFit& fit) {
  ModalProxyFrame f;
  const double norm = std::sqrt(fit.a_m * fit.a_m + fit.b_m * fit.b_m + fit.c_m * fit.c_m);
  f.unit_axes = {fit.c_m / norm, fit.b_m / norm, fit.a_m / norm};
  // fit.axes columns: x (a, smallest moment), y, z (c, largest). Proxy x = fit z, proxy z = fit x;
  // swapping two axes reflects, so proxy y = -fit y keeps the rotation proper.
  for (std::size_t j = 0; j < 3; ++j) {
    f.rotation[0][j] = fit.axes[j][2];
    f.rotation[1][j] = -fit.axes[j][1];
    f.rotation[2][j] = fit.axes[j][0];
  }
  return f;
}

Vec3 to_modal_frame(const ModalProxyFrame& f, const Vec3& v) {
  Vec3 out{};
  for (std::size_t i = 0; i < 3; ++i) out[i] = f.rotation[i][0] * v[0] + f.rotation[i][1] * v[1] + f.rotation[i][2] * v[2];
  return out;
}

Vec3 contact_point(const std::array<double, 3>& a, const Vec3& n) {
  double d = 0;
  for (std::size_t i = 0; i < 3; ++i) d += a[i] * a[i] * n[i] * n[i];
  d = std::sqrt(d);
  return {a[0] * a[0] * n[0] / d, a[1] * a[1] * n[1] / d, a[2] * a[2] * n[2] / d};
}

}  // namespace clatter::kernels::modal
