#pragma once

namespace clatter::kernels {

// The acceleration pulse psi(t; h) of Chadwick, Zheng & James 2012, eq. (6): a C1 cubic
// interpolating kernel supported on [-2h, 2h], centred on t = 0, with y = 1 - |t|/h:
//   psi = (-15 y^3 + 18 y^2 + 9 y + 2) / 18     for |t| <= h
//   psi = (5 (1+y)^3 - 3 (1+y)^2) / 18          for h <= |t| <= 2h
// It is a partition of unity (sum_k psi(t - k h; h) = 1 for every t) and integrates to h, so a
// rigid-body acceleration z(t) = sum_k z(kh) psi(t - kh; h) is reproduced exactly for constants.
double pulse(double t_s, double h_s);

// Pressure [Pa] at distance r from a point monopole in free space whose volume acceleration is
// psi(t; h) [m^3/s^2]: p(r, t) = rho psi(t - r/c; h) / (4 pi r)  (linear acoustics, r > 0).
double monopole_pressure(double r_m, double t_s, double h_s, double c_m_s, double rho_kg_m3);

}  // namespace clatter::kernels
