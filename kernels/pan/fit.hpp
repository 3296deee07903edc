#pragma once
// One direction of one field of a PAN bank from a solve (Chadwick et al. 2012, section 4.1, with
// the radial model of kernels/pan/radial.hpp in place of the series (8)): the pressure at M radii,
// shifted to retarded time, p(R_i, t + R_i/c), and the far field F, each transformed to the wavelet
// basis; stored per coefficient j as F^j and D_i^j = R_i p_i^j - F^j, keeping coefficient j iff
// |F^j| >= eps ||F||_inf or |p_i^j| >= eps ||p_i||_inf for some radius i.
// The radii are whole numbers of time steps, R_i = K_i c dt, so the shift is exact.
#include <array>
#include <cstdint>
#include <vector>

#include "kernels/pan/wavelet.hpp"
#include "model/pan_bank.hpp"

namespace clatter::kernels::pan {

class Fitter {
 public:
  // radii_m ascending, radii_m[i] = shift_steps[i] * c * dt; `length` (a power of two) is T, the
  // wavelet length.
  Fitter(std::vector<double> radii_m, std::vector<int> shift_steps, std::size_t length);

  // series[i]: p(R_i, t_n) for n = 0 .. n_samples-1 (t_n = t_first + n dt). `delay_steps` aligns
  // this direction further by whole steps: coefficient sample n is p(R_i, t_first + (n + shift_i - delay) dt).
  // far_field: length() samples on the same retarded frame, sample n the far field R p at
  // tau = t_first + (n + shift_i - delay) dt - R_i / c. The result is one direction of a bank's
  // field as stored (model/pan_bank.hpp).
  model::SparseTerms fit(const std::vector<const float*>& series, std::size_t n_samples, double epsilon,
                         int delay_steps, const std::vector<double>& far_field) const;

  std::size_t length() const { return wavelet_.length(); }

 private:
  std::vector<double> radii_m_;
  std::vector<int> shift_;
  Wavelet wavelet_;
};

// The direction's first-arrival advance in steps: the ellipsoid's support distance
// h(d) = sqrt(A^2 dx^2 + B^2 dy^2 + C^2 dz^2) (d a unit vector) over c dt. Aligning each direction
// by it (on top of R/c) lines up the pulses of neighbouring directions, so interpolating between
// them does not smear a pulse that arrives earlier on one side of the body (docs/pan.md). A bank
// stores each direction aligned by exactly this (its whole steps in the fit, its fraction through
// the Kirchhoff surface), and the evaluator shifts by it at the query direction: any two direction
// sets then agree on the time frame, and nothing about it is stored.
double support_delay_samples(const std::array<double, 3>& direction, double a_m, double b_m, double c_m, double c_m_s,
                             double dt_s);
// The same for a bank entry: its ellipsoid's, or for a mesh entry the support distance of its
// support points, max_k d . x_k (the normalized mesh's convex hull).
double support_delay_samples(const std::array<double, 3>& direction, double a_m, const model::PanProxy& entry,
                             double c_m_s, double dt_s);
double support_delay_samples(const std::array<double, 3>& direction, double a_m, double b_m, double c_m,
                             const model::PanMeshBody& mesh, double c_m_s, double dt_s);
// The vertices among `points` that are farthest along at least one of a fixed set of directions
// (a Fibonacci sphere of `directions` points): convex-hull vertices, in first-seen order. For a
// stored support set only the reproducibility matters: fit and evaluation use the same points.
std::vector<std::array<double, 3>> support_points(const std::vector<std::array<double, 3>>& points, int directions = 1024);

}  // namespace clatter::kernels::pan
