#pragma once
// The PAN fit of Chadwick et al. 2012, section 4.1, for one direction and one field:
//   p(R_i, t + R_i/c) = sum_{k=1..N} R_i^-k q_k(t)                                   (13)
// transformed to the wavelet basis and solved coefficient by coefficient,
//   p^_i^j = sum_k R_i^-k q^_k^j   (M x N least squares, one pseudo-inverse for all j)  (14)
// keeping coefficient j iff |p^_i^j| >= eps ||p^_i||_inf for some radius i.
// The radii are whole numbers of time steps, R_i = K_i c dt, so the shift is exact.
#include <array>
#include <cstdint>
#include <vector>

#include "kernels/pan/wavelet.hpp"
#include "model/pan_bank.hpp"

namespace clatter::kernels::pan {

class Fitter {
 public:
  // radii_m[i] = shift_steps[i] * c * dt; `length` (a power of two) is T, the wavelet length.
  Fitter(std::vector<double> radii_m, std::vector<int> shift_steps, int terms, std::size_t length);

  // series[i]: p(R_i, t_n) for n = 0 .. n_samples-1 (t_n = t_first + n dt). `delay_steps` aligns
  // this direction further: coefficient sample n is p(R_i, t_first + (n + shift_i - delay) dt).
  // The result is one direction of a bank's field as stored (model/pan_bank.hpp).
  //
  // With `far_field` (length(), on the coefficients' retarded time: sample n is the far field R p
  // at tau = t_first + (n + shift_i - delay) dt - R_i / c), q_1 is the far field itself and only
  // q_2 .. q_N are fitted, to p(R_i) - q_1 / R_i: the series then tends to the true far field
  // however few radii were fitted. A coefficient is also kept where the far field's reaches
  // epsilon of its peak. Needs terms() >= 1; with one term nothing is fitted.
  model::SparseTerms fit(const std::vector<const float*>& series, std::size_t n_samples, double epsilon,
                         int delay_steps = 0, const std::vector<double>* far_field = nullptr) const;

  int terms() const { return terms_; }
  std::size_t length() const { return wavelet_.length(); }

 private:
  std::vector<double> radii_m_;
  std::vector<int> shift_;
  int terms_;
  std::vector<double> pinv_;       // [N][M]
  std::vector<double> pinv_near_;  // [N - 1][M]: q_2 .. q_N alone
  Wavelet wavelet_;
};

// The direction's first-arrival advance in whole steps: the ellipsoid's support distance
// h(d) = sqrt(A^2 dx^2 + B^2 dy^2 + C^2 dz^2) over c dt. Aligning each direction by it (on top of
// R/c) lines up the pulses of neighbouring directions, so interpolating between them does not smear
// a pulse that arrives earlier on one side of the body (docs/pan.md).
int support_delay_steps(const std::array<double, 3>& direction, double a_m, double b_m, double c_m, double c_m_s,
                        double dt_s);

// Adds w * sum_k R^-k q^_k into `coefficients` (length T): the wavelet coefficients of the
// shifted pressure p(R, t + R/c) contributed by one direction vertex with weight w.
void accumulate(const model::SparseTerms& terms, int n_terms, double radius_m, double weight, std::vector<double>& coefficients);

}  // namespace clatter::kernels::pan
