#pragma once
// Spherical Bessel, Neumann and Hankel functions and orthonormal spherical harmonics, by
// recurrences that stay stable at the orders a multipole expansion of a ringing proxy needs
// (n up to a few hundred, x up to a few hundred). tests/unit/test_special_functions.cpp checks
// them against GSL, the Wronskian and large-order and large-argument asymptotics.
#include <complex>
#include <vector>

namespace clatter::kernels::transfer {

// j_n(x), n = 0..n_max, x >= 0: Miller's downward recurrence normalized by the sum rule
// sum (2n + 1) j_n^2 = 1, which holds for every x (no division by a small j_0 near its zeros).
std::vector<double> spherical_bessel_j(int n_max, double x);

// y_n(x), n = 0..n_max, x > 0: upward recurrence (y_n is the dominant solution, so it is stable);
// values beyond the double range come out as -inf, never as a library abort.
std::vector<double> spherical_bessel_y(int n_max, double x);

// h_n^(2)(x) = j_n(x) - i y_n(x): the outgoing wave for the e^{+i omega t} convention of 003
// (free-space Green's function e^{-ikr} / (4 pi r)).
std::vector<std::complex<double>> spherical_hankel2(int n_max, double x);

// The same into out[0..n_max] by the upward recurrence h_{n+1} = (2n+1)/x h_n - h_{n-1} from
// h_0 = i e^{-ix}/x, h_1 = (i/x - 1) e^{-ix}/x: h_n itself is dominant (y_n grows past n > x), so
// every h_n keeps its relative accuracy, without Miller's start above x. Its j_n part alone does
// not (use spherical_bessel_j for that). For expansions evaluated outside their sources.
void spherical_hankel2_upward(int n_max, double x, std::complex<double>* out);

// d/dx h_n^(2)(x) from h_{n-1} - (n + 1) / x h_n (n >= 1) and h_0' = -h_1.
std::vector<std::complex<double>> spherical_hankel2_derivative(const std::vector<std::complex<double>>& h, double x);

// Index of (n, m), |m| <= n, in the flat arrays below: n^2 + n + m.
constexpr int harmonic_index(int n, int m) { return n * n + n + m; }
constexpr int harmonic_count(int n_max) { return (n_max + 1) * (n_max + 1); }

// Y_n^m(theta, phi), orthonormal on the unit sphere, Condon-Shortley phase, for every n <= n_max:
// out[harmonic_index(n, m)]. Y_n^{-m} = (-1)^m conj(Y_n^m).
void spherical_harmonics(int n_max, double cos_theta, double phi, std::complex<double>* out);

}  // namespace clatter::kernels::transfer
