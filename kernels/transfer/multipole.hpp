#pragma once
// A mode's acoustic transfer as a single-point multipole expansion about the proxy's centre
// (003 eqs. 6-7): p(x) = sum_{n <= order} sum_m M_n^m h_n^(2)(k r) Y_n^m(theta, phi), with the
// e^{+i omega t} convention and orthonormal Y_n^m (Condon-Shortley), valid outside the sphere
// that holds the sources it was built from. p is the complex pressure amplitude [Pa] per unit
// modal amplitude.
#include <Eigen/Core>
#include <complex>
#include <span>
#include <vector>

#include "model/modal_bank.hpp"

namespace clatter::kernels::transfer {

struct Multipole {
  double k_rad_m = 0;                           // wavenumber omega / c
  int order = 0;                                // n-bar
  std::vector<std::complex<double>> coefficients;  // M_n^m at harmonic_index(n, m), (order + 1)^2

  std::complex<double> pressure(const Eigen::Vector3d& x_m) const;
};

// |p(x)| of several expansions about the same centre (a proxy's modes at one listener): the
// harmonics are evaluated once, at the highest order, and each mode adds only its Hankel terms.
void pressure_magnitudes(std::span<const Multipole* const> modes, const Eigen::Vector3d& x_m, double* out);

// Adds to `coefficients` (size harmonic_count(order)) the expansion of a monopole
// strength * e^{-ik|x - y|} / (4 pi |x - y|) at y (valid for |x| > |y|):
// -ik strength j_n(k|y|) conj(Y_n^m(y-hat)) (Gumerov & Duraiswami 2004, eq. 2.1.91, conjugated).
void add_monopole(double k_rad_m, int order, const Eigen::Vector3d& y_m, std::complex<double> strength,
                  std::vector<std::complex<double>>& coefficients);

// The same for the 8 mirror images of y (mirror s: ellipsoid_points.hpp) in several parity
// classes: image s with strength parity_sign(s, sigmas[c]) * strengths[c] for each class c, summed
// in closed form from Y_n^m(y-hat) alone (flipping x maps conj Y_n^m to (-1)^m Y_n^m, flipping y to
// Y_n^m, flipping z multiplies by (-1)^(n+m)); the Bessel functions and harmonics, most of the
// cost, once for all the classes.
void add_mirrored_monopole(double k_rad_m, int order, const Eigen::Vector3d& y_m,
                           std::span<const std::complex<double>> strengths, std::span<const int> sigmas,
                           std::vector<std::complex<double>>& coefficients);

// The order at which the expansion of sources within radius rho [m] is cut before truncation:
// past k rho the terms fall off superexponentially (the k rho + 3 (k rho)^(1/3) rule of the
// fast multipole method), and 20 more keep the geometric tail (rho / r)^n below 1e-6 at r = 2 rho.
int source_order(double k_rad_m, double rho_m);

// The smallest order whose dropped terms hold at most tolerance^2 of the far field's energy
// (sum_m |M_n^m|^2 is the order's share of the far-field pattern's L2 norm).
int truncation_order(const std::vector<std::complex<double>>& coefficients, int order, double tolerance);

// The time-averaged power [W] the expansion radiates per unit modal amplitude: in the far field
// h_n^(2)(kr) -> i^(n+1) e^{-ikr} / (kr), so r^2 |p|^2 integrated over directions is
// sum |M_n^m|^2 / k^2 (orthonormal Y_n^m), and the intensity |p|^2 / (2 rho c) gives
//   P = sum |M_n^m|^2 / (2 rho c k^2).
double far_field_power_w(const Multipole& m, double air_density_kg_m3, double sound_speed_m_s);

// Mode `mode` of a bank entry's stored transfer (model/modal_bank.hpp).
Multipole stored_multipole(const model::ModalTransfer& transfer, std::size_t mode);

// The expansion of the same body scaled by gamma (003 eq. 9, Appendix E): k -> k / gamma,
// M -> gamma^(-5/2) M, so p_gamma(gamma x) = gamma^(-5/2) p(x).
Multipole scaled(const Multipole& m, double gamma);

}  // namespace clatter::kernels::transfer
