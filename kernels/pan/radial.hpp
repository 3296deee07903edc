#pragma once
// How a PAN field varies with distance along one direction (docs/pan.md, "The radial model").
// The bank stores, per wavelet coefficient, R p(R, tau + R/c) at M radii R_1 < ... < R_M and its
// limit, the far field F = lim R p, at u = 1/R = 0; between them R p is the cubic in u through
// the four nodes around u (the two innermost radii's line inside R_1). Stored as F and the
// residuals D_i = R_i p(R_i) - F, so that
//   p(R) = u F + u sum_i L_i(u) D_i          (L_i: the cubic's Lagrange weights, sum with F's = 1)
// The paper's series (8), p = sum_k q_k / R^k fitted over 0.7-1.5 m, needs many terms where
// listeners are (1-5 m lies in an elongated proxy's Fresnel region at the paper's pulse, docs/pan.md)
// and a few fitted terms extrapolate nowhere; interpolation in 1/R with the far field as its end
// node holds 0.2 % from the innermost radius to infinity (measured, docs/pan.md).
#include <array>
#include <cstddef>
#include <vector>

#include "model/pan_bank.hpp"

namespace clatter::kernels::pan {

// p(R) = far v_0 + sum_{k < count} near[k] v_{first + k}, for the stored values
// v = (F, D_1, ..., D_M) of one kept coefficient.
struct RadialWeights {
  double far = 0;
  int first = 1, count = 0;
  std::array<double, 4> near{};
};

// radii_m ascending, positive; r_m > 0. No allocation (called per impact).
RadialWeights radial_weights(const std::vector<double>& radii_m, double r_m);

// Adds weight * p^j(R) into coefficients[j] for every kept j of one direction: the wavelet
// coefficients of p(R, t + R/c) contributed by one direction vertex. `values` per kept
// coefficient: M + 1 (PanBankHeader::values()).
void accumulate(const model::SparseTerms& terms, std::size_t values, const RadialWeights& w, double weight,
                std::vector<double>& coefficients);

}  // namespace clatter::kernels::pan
