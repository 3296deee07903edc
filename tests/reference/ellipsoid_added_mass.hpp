#pragma once
// The low-frequency dipole of a rigid ellipsoid translating in an ideal fluid (Lamb, Hydrodynamics,
// 6th ed., sections 114-115): with semi-axes (a, b, c) and the shape integral along the axis of motion
//   alpha = abc int_0^inf dl / ((s^2 + l) sqrt((a^2 + l)(b^2 + l)(c^2 + l))),  s the semi-axis along it,
// the far potential of the translation U is that of a dipole of strength M U, M = V + m_added / rho =
// 2 V / (2 - alpha) (V the volume); a sphere has alpha = 2/3, M = 3V/2. In Carlson's form
// alpha = (2/3) abc R_D(t^2, u^2, s^2), (t, u) the other two semi-axes. The radiated far field of an
// acceleration A(t) along that axis is then p = rho M cos(theta) A'(t - r/c) / (4 pi c r) as omega -> 0
// (docs/validation.md, "Thin proxies against Lamb's added mass").
namespace clatter::reference {

// M [m^3] of the ellipsoid (a, b, c) translating along axis 0, 1 or 2 (the a, b or c axis).
double ellipsoid_translation_dipole_m3(double a_m, double b_m, double c_m, int axis);

}  // namespace clatter::reference
