#include "kernels/pan/fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace clatter::kernels::pan {

Fitter::Fitter(std::vector<double> radii_m, std::vector<int> shift_steps, int terms, std::size_t length)
    : radii_m_(std::move(radii_m)), shift_(std::move(shift_steps)), terms_(terms), wavelet_(length) {
  const int m = static_cast<int>(radii_m_.size());
  if (m < terms || terms < 1 || shift_.size() != radii_m_.size())
    throw std::invalid_argument("PAN fit needs at least as many radii as series terms");
  // The pseudo-inverse of the M x K matrix R_i^-(first + k), row-major [K][M].
  auto pinv = [&](int first, int count) {
    std::vector<double> out(static_cast<std::size_t>(count) * static_cast<std::size_t>(m));
    if (count == 0) return out;
    Eigen::MatrixXd v(m, count);
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < count; ++k) v(i, k) = std::pow(radii_m_[static_cast<std::size_t>(i)], -(first + k));
    const Eigen::MatrixXd p = v.completeOrthogonalDecomposition().pseudoInverse();
    for (int k = 0; k < count; ++k)
      for (int i = 0; i < m; ++i) out[static_cast<std::size_t>(k * m + i)] = p(k, i);
    return out;
  };
  pinv_ = pinv(1, terms);
  pinv_near_ = pinv(2, terms - 1);
}

int support_delay_steps(const std::array<double, 3>& d, double a_m, double b_m, double c_m, double c_m_s, double dt_s) {
  const double h = std::sqrt(a_m * a_m * d[0] * d[0] + b_m * b_m * d[1] * d[1] + c_m * c_m * d[2] * d[2]);
  return static_cast<int>(std::lround(h / (c_m_s * dt_s)));
}

model::SparseTerms Fitter::fit(const std::vector<const float*>& series, std::size_t n_samples, double epsilon,
                               int delay_steps, const std::vector<double>* far_field) const {
  const std::size_t m = radii_m_.size(), n = wavelet_.length();
  if (series.size() != m) throw std::invalid_argument("PAN fit: one series per radius");
  if (far_field && far_field->size() != n) throw std::invalid_argument("PAN fit: the far field is not one wavelet length");
  std::vector<std::vector<double>> coef(m, std::vector<double>(n, 0.0));
  std::vector<double> peak(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    // Shift by R_i / c = K_i steps (less the direction's delay); before the record starts and
    // after it ends the field is at rest (zero).
    const long k0 = static_cast<long>(shift_[i]) - delay_steps;
    for (std::size_t t = 0; t < n; ++t) {
      const long k = k0 + static_cast<long>(t);
      if (k >= 0 && k < static_cast<long>(n_samples)) coef[i][t] = series[i][static_cast<std::size_t>(k)];
    }
    wavelet_.forward(coef[i]);
    for (double c : coef[i]) peak[i] = std::max(peak[i], std::abs(c));
  }
  std::vector<double> far;
  double far_peak = 0;
  if (far_field) {
    far = *far_field;
    wavelet_.forward(far);
    for (double c : far) far_peak = std::max(far_peak, std::abs(c));
  }
  model::SparseTerms out;
  for (std::size_t j = 0; j < n; ++j) {
    bool keep = far_field && far_peak > 0 && std::abs(far[j]) >= epsilon * far_peak;
    for (std::size_t i = 0; i < m && !keep; ++i) keep = peak[i] > 0 && std::abs(coef[i][j]) >= epsilon * peak[i];
    if (!keep) continue;
    out.index.push_back(static_cast<std::uint32_t>(j));
    if (!far_field) {
      for (int k = 0; k < terms_; ++k) {
        double q = 0;
        for (std::size_t i = 0; i < m; ++i) q += pinv_[static_cast<std::size_t>(k) * m + i] * coef[i][j];
        out.value.push_back(static_cast<float>(q));
      }
      continue;
    }
    out.value.push_back(static_cast<float>(far[j]));
    for (int k = 0; k + 1 < terms_; ++k) {
      double q = 0;
      for (std::size_t i = 0; i < m; ++i)
        q += pinv_near_[static_cast<std::size_t>(k) * m + i] * (coef[i][j] - far[j] / radii_m_[i]);
      out.value.push_back(static_cast<float>(q));
    }
  }
  return out;
}

void accumulate(const model::SparseTerms& terms, int n_terms, double radius_m, double weight, std::vector<double>& coefficients) {
  // Called per vertex and field for every impact the synthesizer renders: no allocation, no pow.
  std::array<double, 8> scale{};
  if (n_terms < 1 || n_terms > static_cast<int>(scale.size())) throw std::invalid_argument("PAN accumulate: 1 to 8 terms");
  const double inv_r = 1.0 / radius_m;
  double power = weight * inv_r;
  for (int k = 0; k < n_terms; ++k, power *= inv_r) scale[static_cast<std::size_t>(k)] = power;
  const std::size_t n_kept = terms.index.size(), size = coefficients.size();
  if (n_terms == 2) {  // the default N: the same sums, unrolled (a quarter of the synthesizer's time is here)
    const double s0 = scale[0], s1 = scale[1];
    const float* v = terms.value.data();
    for (std::size_t e = 0; e < n_kept; ++e) {
      const std::size_t j = terms.index[e];
      if (j >= size) break;
      double s = 0;
      s += s0 * v[2 * e];
      s += s1 * v[2 * e + 1];
      coefficients[j] += s;
    }
    return;
  }
  for (std::size_t e = 0; e < n_kept; ++e) {
    const std::size_t j = terms.index[e];
    if (j >= size) break;  // Algorithm 1 dropped the finest levels (indices ascend)
    double s = 0;
    for (int k = 0; k < n_terms; ++k)
      s += scale[static_cast<std::size_t>(k)] * terms.value[e * static_cast<std::size_t>(n_terms) + static_cast<std::size_t>(k)];
    coefficients[j] += s;
  }
}

}  // namespace clatter::kernels::pan
