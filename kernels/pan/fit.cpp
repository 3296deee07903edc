#include "kernels/pan/fit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace clatter::kernels::pan {

Fitter::Fitter(std::vector<double> radii_m, std::vector<int> shift_steps, std::size_t length)
    : radii_m_(std::move(radii_m)), shift_(std::move(shift_steps)), wavelet_(length) {
  if (shift_.size() != radii_m_.size()) throw std::invalid_argument("PAN fit: one shift per radius");
  for (std::size_t i = 0; i < radii_m_.size(); ++i)
    if (!(radii_m_[i] > 0) || (i > 0 && !(radii_m_[i] > radii_m_[i - 1])))
      throw std::invalid_argument("PAN fit: the radii must be positive and ascending");
}

double support_delay_samples(const std::array<double, 3>& d, double a_m, double b_m, double c_m, double c_m_s,
                             double dt_s) {
  const double h = std::sqrt(a_m * a_m * d[0] * d[0] + b_m * b_m * d[1] * d[1] + c_m * c_m * d[2] * d[2]);
  return h / (c_m_s * dt_s);
}

double support_delay_samples(const std::array<double, 3>& d, double a_m, double b_m, double c_m,
                             const model::PanMeshBody& mesh, double c_m_s, double dt_s) {
  if (mesh.key.empty()) return support_delay_samples(d, a_m, b_m, c_m, c_m_s, dt_s);
  double h = -HUGE_VAL;
  for (const auto& x : mesh.support_points_m) h = std::max(h, d[0] * x[0] + d[1] * x[1] + d[2] * x[2]);
  return h / (c_m_s * dt_s);
}

double support_delay_samples(const std::array<double, 3>& d, double a_m, const model::PanProxy& entry, double c_m_s,
                             double dt_s) {
  return support_delay_samples(d, a_m, entry.b_m, entry.c_m, entry.mesh, c_m_s, dt_s);
}

std::vector<std::array<double, 3>> support_points(const std::vector<std::array<double, 3>>& points, int directions) {
  std::vector<char> kept(points.size(), 0);
  std::vector<std::array<double, 3>> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < directions && !points.empty(); ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / directions, r = std::sqrt(1.0 - z * z);
    const std::array<double, 3> d{r * std::cos(golden * k), r * std::sin(golden * k), z};
    std::size_t best = 0;
    double h = -HUGE_VAL;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double s = d[0] * points[i][0] + d[1] * points[i][1] + d[2] * points[i][2];
      if (s > h) {
        h = s;
        best = i;
      }
    }
    if (!kept[best]) {
      kept[best] = 1;
      out.push_back(points[best]);
    }
  }
  return out;
}

model::SparseTerms Fitter::fit(const std::vector<const float*>& series, std::size_t n_samples, double epsilon,
                               int delay_steps, const std::vector<double>& far_field) const {
  const std::size_t m = radii_m_.size(), n = wavelet_.length();
  if (series.size() != m) throw std::invalid_argument("PAN fit: one series per radius");
  if (far_field.size() != n) throw std::invalid_argument("PAN fit: the far field is not one wavelet length");
  std::vector<std::vector<double>> coef(m, std::vector<double>(n, 0.0));
  std::vector<double> peak(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    // Shift by R_i / c = K_i steps (less the direction's delay); before the record starts and
    // after it ends the field is at rest (zero).
    const long k0 = static_cast<long>(shift_[i]) - delay_steps;
    for (std::size_t t = 0; t < n; ++t) {
      const long k = k0 + static_cast<long>(t);
      if (k >= 0 && k < static_cast<long>(n_samples)) coef[i][t] = radii_m_[i] * series[i][static_cast<std::size_t>(k)];
    }
    wavelet_.forward(coef[i]);
    for (double c : coef[i]) peak[i] = std::max(peak[i], std::abs(c));
  }
  std::vector<double> far = far_field;
  wavelet_.forward(far);
  double far_peak = 0;
  for (double c : far) far_peak = std::max(far_peak, std::abs(c));
  model::SparseTerms out;
  for (std::size_t j = 0; j < n; ++j) {
    bool keep = far_peak > 0 && std::abs(far[j]) >= epsilon * far_peak;
    for (std::size_t i = 0; i < m && !keep; ++i) keep = peak[i] > 0 && std::abs(coef[i][j]) >= epsilon * peak[i];
    if (!keep) continue;
    out.index.push_back(static_cast<std::uint32_t>(j));
    out.value.push_back(static_cast<float>(far[j]));
    for (std::size_t i = 0; i < m; ++i) out.value.push_back(static_cast<float>(coef[i][j] - far[j]));
  }
  return out;
}

}  // namespace clatter::kernels::pan
