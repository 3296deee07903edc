#pragma once
// Spherical Bessel, Neumann and Hankel functions and orthonormal spherical harmonics, by
// recurrences that stay stable at the orders a multipole expansion of a ringing proxy needs
// (n up to a few hundred, x up to a few hundred). tests/unit/test_special_functions.cpp checks
// them against GSL, the Wronskian and large-order and large-argument asymptotics.
#include <cmath>
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

// sin x and cos x for the Green's functions' k r, ~4x faster than libm's sincos here (the
// equivalent sources' fill spends most of its time in them): x reduced by the nearest multiple of
// pi / 2 in three parts (fdlibm's pio2_1..3: n pio2_1 is exact for |n| < 2^20), then Cephes'
// minimax polynomials on [-pi / 4, pi / 4]. Within 2.3e-16 of libm for |x| <= 1e5
// (tests/unit/test_special_functions.cpp); libm itself beyond.
// sin_cos for |x| <= kSinCosReduced (the caller's check), without branches: the quadrant picks
// by selects, so that a loop of them vectorizes (equivalent_sources.cpp's 8 images).
inline constexpr double kSinCosReduced = 1e5;
inline void sin_cos_reduced(double x, double& sin_x, double& cos_x) {
  constexpr double kTwoOverPi = 0.636619772367581343076;
  constexpr double kPio2_1 = 1.57079632673412561417e+00, kPio2_2 = 6.07710050630396597660e-11,
                   kPio2_3 = 2.02226624871116645580e-21;
  const double n = std::nearbyint(x * kTwoOverPi);
  const double y = ((x - n * kPio2_1) - n * kPio2_2) - n * kPio2_3, z = y * y;
  const double s = y + y * z * (-1.66666666666666307295e-1 + z * (8.33333333332211858878e-3 + z * (-1.98412698295895385996e-4 +
                   z * (2.75573136213857245213e-6 + z * (-2.50507477628578072866e-8 + z * 1.58962301576546568060e-10)))));
  const double c = 1.0 - 0.5 * z + z * z * (4.16666666666665929218e-2 + z * (-1.38888888888730564116e-3 + z * (2.48015872888517045348e-5 +
                   z * (-2.75573141792967388112e-7 + z * (2.08757008419747316778e-9 + z * -1.13585365213876817300e-11)))));
  // Quadrant q = n mod 4: sin is s, c, -s, -c and cos is c, -s, -c, s.
  const int q = static_cast<int>(n) & 3;
  const double s_q = (q & 1) ? c : s, c_q = (q & 1) ? s : c;
  sin_x = (q & 2) ? -s_q : s_q;
  cos_x = ((q + 1) & 2) ? -c_q : c_q;
}
inline void sin_cos(double x, double& sin_x, double& cos_x) {
  if (!(std::abs(x) <= kSinCosReduced)) {
    sin_x = std::sin(x);
    cos_x = std::cos(x);
    return;
  }
  sin_cos_reduced(x, sin_x, cos_x);
}

// Index of (n, m), |m| <= n, in the flat arrays below: n^2 + n + m.
constexpr int harmonic_index(int n, int m) { return n * n + n + m; }
constexpr int harmonic_count(int n_max) { return (n_max + 1) * (n_max + 1); }

// Y_n^m(theta, phi), orthonormal on the unit sphere, Condon-Shortley phase, for every n <= n_max:
// out[harmonic_index(n, m)]. Y_n^{-m} = (-1)^m conj(Y_n^m).
void spherical_harmonics(int n_max, double cos_theta, double phi, std::complex<double>* out);

}  // namespace clatter::kernels::transfer
