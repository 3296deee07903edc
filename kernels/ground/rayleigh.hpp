#pragma once
// Sound radiated into the air by the normal acceleration of the ground surface, taken as a
// rigid-baffled plane, by the Rayleigh integral (Qu & James, seed 004, eq. 12):
//   p(x, t) = rho_0 int_{R^2} a(r', t - R'/c_0) / (2 pi R') dA',
// for a surface acceleration axisymmetric about the impact point (Lamb's problem under a vertical
// load). In polar coordinates (s, psi) about the listener's foot, with R^2 = s^2 + z^2 and
// dA = s ds dpsi = R dR dpsi, the 1/R singularity under the listener cancels:
//   p = (rho_0 / 2 pi) int_z^{R_end} dR  2 int_0^{psi_max(R)} a(r'(s, psi), t - R/c_0) dpsi,
//   r'^2 = rho^2 + s^2 - 2 rho s cos psi.
// The field vanishes beyond a support radius r_max(tau) (a causal field's fastest front, or where a
// regularized field is cut off: the domain truncation), so each ring only meets the disk r' <=
// r_max for |psi| <= psi_max, and rings stop at R_end, where s = rho + r_max(t - R/c_0) (or
// R = c_0 t: nothing is emitted before the impact). Both integrals are composite Gauss-Legendre
// with panels no longer than the field's resolution length (in R, and in arc length s psi), ending
// exactly on those edges, so a field with a sharp front converges as fast as a smooth one.
// Not for Lamb's field: its 1/r at the impact point becomes an inverse-square-root end in R under
// an overhead listener, where these panels do not converge; ground_response.hpp integrates it
// about the impact point instead (docs/ground.md).
#include <functional>

namespace clatter::kernels::ground {

struct SurfaceField {
  // The normal acceleration towards the air [m/s^2] at distance r [m] from the impact point,
  // tau [s] after the impact.
  std::function<double(double r_m, double tau_s)> acceleration;
  // a(r, tau) = 0 for r > support_radius_m(tau); non-decreasing in tau (infinity allowed).
  std::function<double(double tau_s)> support_radius_m;
};

struct RayleighSettings {
  double c0_m_s = 343.2, rho0_kg_m3 = 1.2041;  // the air (the transfer's defaults)
  double resolution_m = 5e-3;                   // the longest quadrature panel: a fraction of the field's shortest length
  int nodes_per_panel = 8;                      // Gauss-Legendre points per panel (exact for degree 15)
};

struct RayleighPressure {
  double pressure_pa = 0;
  long evaluations = 0;  // of the surface field
};

// The pressure at a listener at horizontal distance rho_m >= 0 from the impact point and height
// z_m > 0 above the surface, t_s after the impact. std::invalid_argument for a listener on or
// below the surface, rho_m < 0, or settings that cannot integrate.
RayleighPressure rayleigh_pressure(const SurfaceField& field, double rho_m, double z_m, double t_s,
                                   const RayleighSettings& settings = {});

}  // namespace clatter::kernels::ground
