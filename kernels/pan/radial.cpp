#include "kernels/pan/radial.hpp"

#include <algorithm>
#include <stdexcept>

namespace clatter::kernels::pan {

RadialWeights radial_weights(const std::vector<double>& radii_m, double r_m) {
  RadialWeights w;
  const double u = 1.0 / r_m;
  w.far = u;
  const int m = static_cast<int>(radii_m.size());
  if (m == 0) return w;
  // Nodes in u ascending: node 0 is the far field (residual 0, nothing stored), node j >= 1 is
  // radius M + 1 - j, stored as value M + 1 - j.
  auto node = [&](int j) { return j == 0 ? 0.0 : 1.0 / radii_m[static_cast<std::size_t>(m - j)]; };
  int lo = 0, n = 0;
  if (u > node(m)) {
    // Inside the innermost radius: the line through the two innermost nodes, R p = a + b / R,
    // which is the paper's two-term series there (a cubic would extrapolate wildly).
    lo = m - 1;
    n = 2;
  } else {
    int k = 0;  // the interval node(k) <= u <= node(k + 1)
    while (k + 1 < m && u >= node(k + 1)) ++k;
    n = std::min(4, m + 1);
    lo = std::clamp(k - 1, 0, m + 1 - n);  // the interval's two neighbours on each side where they exist
  }
  w.first = m + 2 - lo - n;  // value index of the stencil's last (innermost) node
  w.count = 0;
  for (int j = lo; j < lo + n; ++j) {
    if (j == 0) continue;
    double l = 1;
    for (int i = lo; i < lo + n; ++i)
      if (i != j) l *= (u - node(i)) / (node(j) - node(i));
    const int value = m + 1 - j;
    w.near[static_cast<std::size_t>(value - w.first)] = u * l;
    w.count = std::max(w.count, value - w.first + 1);
  }
  return w;
}

void accumulate(const model::SparseTerms& terms, std::size_t values, const RadialWeights& w, double weight,
                std::vector<double>& coefficients) {
  // Called per vertex and field for every impact the synthesizer renders: no allocation.
  if (w.first < 1 || w.count < 0 || static_cast<std::size_t>(w.first + w.count) > values)
    throw std::invalid_argument("PAN accumulate: radial weights outside the stored values");
  const double far = weight * w.far;
  std::array<double, 4> near{};
  for (int k = 0; k < w.count; ++k) near[static_cast<std::size_t>(k)] = weight * w.near[static_cast<std::size_t>(k)];
  const std::size_t n_kept = terms.index.size(), size = coefficients.size(), first = static_cast<std::size_t>(w.first);
  const float* v = terms.value.data();
  if (w.count == 4) {  // between two radii or beyond the outermost: the common case, unrolled
    const double a = near[0], b = near[1], c = near[2], d = near[3];
    for (std::size_t e = 0; e < n_kept; ++e, v += values) {
      const std::size_t j = terms.index[e];
      if (j >= size) break;  // Algorithm 1 dropped the finest levels (indices ascend)
      coefficients[j] += far * v[0] + a * v[first] + b * v[first + 1] + c * v[first + 2] + d * v[first + 3];
    }
    return;
  }
  for (std::size_t e = 0; e < n_kept; ++e, v += values) {
    const std::size_t j = terms.index[e];
    if (j >= size) break;
    double s = far * v[0];
    for (int k = 0; k < w.count; ++k) s += near[static_cast<std::size_t>(k)] * v[first + static_cast<std::size_t>(k)];
    coefficients[j] += s;
  }
}

}  // namespace clatter::kernels::pan
