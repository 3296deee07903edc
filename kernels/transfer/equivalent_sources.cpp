#include "kernels/transfer/equivalent_sources.hpp"
#include "kernels/transfer/special_functions.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <span>
#include <string>
#include <numbers>

// LAPACK's least squares (Fortran; the trailing argument is the hidden length of `trans`).
extern "C" void zgels_(const char* trans, const int* m, const int* n, const int* nrhs, std::complex<double>* a,
                       const int* lda, std::complex<double>* b, const int* ldb, std::complex<double>* work,
                       const int* lwork, int* info, std::size_t trans_length);

namespace clatter::kernels::transfer {
namespace {

// The 8 mirror images of a source as coordinate arrays, so that the loops over them vectorize.
struct Images {
  double x[8], y[8], z[8];
};
Images images_of(const Eigen::Vector3d& y) {
  Images m;
  for (int t = 0; t < 8; ++t) {
    const Eigen::Vector3d image = mirror(y, t);
    m.x[t] = image.x();
    m.y[t] = image.y();
    m.z[t] = image.z();
  }
  return m;
}

// G = e^{-ikr} / (4 pi r) and its gradient in x, -(1 + ikr) e^{-ikr} / (4 pi r^3) (x - y).
// The 8 images of a source seen from point (x, n): G and dG/dn of G(x, mirror_t(y)), real and
// imaginary parts apart. The fill and the check evaluate this ~10^8 times per flat mode, and it,
// not the QR, is most of a mode's time: in real arithmetic, without branches (sin_cos_reduced),
// and cloned for AVX2 (chosen at load time where the CPU has it; 4 images per instruction). No FMA
// in either clone, and IEEE square roots and divisions in both: the same bits on any x86-64.
struct ImageGreens {
  double value_re[8], value_im[8], dn_re[8], dn_im[8];
};
[[gnu::target_clones("avx2", "default")]] void image_greens(double k, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                                                            const Images& images, ImageGreens& out) {
  double r[8], dn[8], kr[8], c[8], sn[8];
  double largest = 0;
  for (int t = 0; t < 8; ++t) {
    const double dx = x.x() - images.x[t], dy = x.y() - images.y[t], dz = x.z() - images.z[t];
    r[t] = std::sqrt(dx * dx + dy * dy + dz * dz);
    dn[t] = dx * n.x() + dy * n.y() + dz * n.z();
    kr[t] = k * r[t];
    largest = std::max(largest, kr[t]);
  }
  if (largest <= kSinCosReduced)
    for (int t = 0; t < 8; ++t) sin_cos_reduced(kr[t], sn[t], c[t]);
  else
    for (int t = 0; t < 8; ++t) sin_cos(kr[t], sn[t], c[t]);
  for (int t = 0; t < 8; ++t) {
    const double inv_r = 1 / r[t], scale = inv_r / (4 * std::numbers::pi);
    const double e_re = c[t] * scale, e_im = -sn[t] * scale, f = -dn[t] * inv_r * inv_r;
    out.value_re[t] = e_re;
    out.value_im[t] = e_im;
    out.dn_re[t] = f * (e_re - kr[t] * e_im);  // -(1 + ikr) e dn / r^2
    out.dn_im[t] = f * (e_im + kr[t] * e_re);
  }
}

// The class sigma's part of a field over the 8 images: sum of parity_sign(t, sigma) times image t.
std::complex<double> class_sum(const double (&re)[8], const double (&im)[8], int sigma) {
  double sum_re = 0, sum_im = 0;
  for (int t = 0; t < 8; ++t) {
    const double sign = parity_sign(t, sigma);
    sum_re += sign * re[t];
    sum_im += sign * im[t];
  }
  return {sum_re, sum_im};
}

// A row's panels: the stretches that one cell of its coarsest level stands for (level l has
// size / panels samples per panel, in order), as bounding spheres of their finest samples.
struct Panel {
  Eigen::Vector3d center;
  double radius_m = 0;
};
std::vector<Panel> panels_of(const SpreadRow& row) {
  const std::size_t panels = row.panels, per = row.levels.front().size() / panels;
  std::vector<Panel> out(panels);
  for (std::size_t j = 0; j < panels; ++j) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (std::size_t q = j * per; q < (j + 1) * per; ++q) c += row.levels.front()[q].position_m;
    c /= static_cast<double>(per);
    double r = 0;
    for (std::size_t q = j * per; q < (j + 1) * per; ++q) r = std::max(r, (row.levels.front()[q].position_m - c).norm());
    out[j] = {c, r};
  }
  return out;
}

// How finely a point sees a panel: the coarsest level whose cells s are within `most_m` and whose
// distance to the panel (less half a cell) is at least `distance` s. A coarser level's two Gauss
// points per cell are off by ~(s / D)^4 / 4320 of the cell's share at distance D, and by
// ~(k s)^4 / 4320 in what radiates; levels are tried coarsest first, so only the panels near a
// point pay for the finer spacings.
struct LevelRule {
  double distance, most_m;
};
std::size_t panel_level(const SpreadRow& row, const Panel& panel, const Eigen::Vector3d& x, const LevelRule& rule) {
  const double d = (x - panel.center).norm() - panel.radius_m;
  for (std::size_t l = row.levels.size(); l-- > 1;)
    if (row.spacing_m[l] <= rule.most_m && d - 0.5 * row.spacing_m[l] >= rule.distance * row.spacing_m[l]) return l;
  return 0;
}

// Calls visit(sample, points) for every sample of `row` with the points that see it: per panel,
// the points grouped by the level they see it at (the images of a sample are the loop's outer
// work, shared by its points).
template <class Visit>
void for_each_sample(const SpreadRow& row, const SurfacePoints& points, const LevelRule& rule, const Visit& visit) {
  const auto panels = panels_of(row);
  std::vector<std::vector<std::size_t>> by_level(row.levels.size());
  for (std::size_t j = 0; j < panels.size(); ++j) {
    for (auto& v : by_level) v.clear();
    for (std::size_t i = 0; i < points.size(); ++i) by_level[panel_level(row, panels[j], points.position_m[i], rule)].push_back(i);
    for (std::size_t l = 0; l < row.levels.size(); ++l) {
      if (by_level[l].empty()) continue;
      const std::size_t per = row.levels[l].size() / panels.size();
      for (std::size_t q = j * per; q < (j + 1) * per; ++q) visit(row.levels[l][q], by_level[l]);
    }
  }
}

// The fill's and the field's (residual, checks) rule: a point at least kLevelDistance cells from a
// panel (2^-4 / 4320 ~ 1.4e-5 of its share), cells within a tenth of the air wavelength (~3.6e-5
// in what radiates). With a midpoint per cell the field needed 4 cells and a 30th of the
// wavelength, and even so read the thinnest entries' lowest residuals 10-15 % low (the cell's
// quadrupole, docs/transfer.md "The check's own accuracy"); with two Gauss points the residual
// reads the same at 2, 4 and 8 cells to 0.5 %, and at a 10th or a 30th of the wavelength.
LevelRule level_rule(double k) { return {kLevelDistance, 2 * std::numbers::pi / k / 10}; }

// Row i, column j of class sigma: sqrt(w_i) d/dn_i of sum_t sign(t, sigma) G(x_i, mirror_t(y_j)),
// for every requested class in one pass over the images (the Green's functions, not the classes,
// are the cost).
std::vector<Eigen::MatrixXcd> system_matrices(double k, const SurfacePoints& fit, const SourceLayout& layout,
                                              const std::vector<int>& sigmas) {
  const auto m = static_cast<Eigen::Index>(fit.size()), n = static_cast<Eigen::Index>(layout.sources.size());
  std::vector<Eigen::MatrixXcd> a(sigmas.size(), Eigen::MatrixXcd::Zero(m, n));
  std::vector<double> root_w(fit.size());
  for (std::size_t i = 0; i < fit.size(); ++i) root_w[i] = std::sqrt(fit.weight_m2[i]);
  std::vector<std::complex<double>> sums(sigmas.size());
  // Adds the column of a monopole at y, times weight(class), to unknowns' columns via `add`.
  const auto accumulate = [&](const Eigen::Vector3d& y, const auto& add) {
    const auto images = images_of(y);
    ImageGreens g;
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      image_greens(k, fit.position_m[ui], fit.normal[ui], images, g);
      for (std::size_t c = 0; c < sigmas.size(); ++c) sums[c] = root_w[ui] * class_sum(g.dn_re, g.dn_im, sigmas[c]);
      add(i);
    }
  };
  if (layout.spread.empty()) {
    for (Eigen::Index j = 0; j < n; ++j)
      accumulate(layout.sources.position_m[static_cast<std::size_t>(j)], [&](Eigen::Index i) {
        for (std::size_t c = 0; c < sigmas.size(); ++c) a[c](i, j) = sums[c];
      });
    return a;
  }
  // A sample's column over the points that see it, then added to each tap's column: down the
  // columns, where adding a point's taps across them missed the cache on every add (the same
  // sums in the same order: an entry's terms still come sample by sample, tap by tap).
  std::vector<std::vector<std::complex<double>>> column(sigmas.size());
  for (const SpreadRow& row : layout.spread)
    for_each_sample(row, fit, level_rule(k), [&](const SpreadPoint& p, const std::vector<std::size_t>& near) {
      const auto images = images_of(p.position_m);
      ImageGreens g;
      for (auto& col : column) col.resize(near.size());
      for (std::size_t q = 0; q < near.size(); ++q) {
        const std::size_t ui = near[q];
        image_greens(k, fit.position_m[ui], fit.normal[ui], images, g);
        for (std::size_t c = 0; c < sigmas.size(); ++c) column[c][q] = root_w[ui] * class_sum(g.dn_re, g.dn_im, sigmas[c]);
      }
      for (std::size_t c = 0; c < sigmas.size(); ++c)
        for (std::size_t tap = 0; tap < p.taps.size(); ++tap) {
          const double w = p.weight_for(tap, sigmas[c]);
          std::complex<double>* target = a[c].col(p.taps[tap].unknown).data();
          for (std::size_t q = 0; q < near.size(); ++q) target[near[q]] += w * column[c][q];
        }
    });
  return a;
}

}  // namespace

// Tikhonov-regularized least squares, min ||A c - b||^2 + mu^2 ||c||^2, as LAPACK's QR least
// squares (zgels) of [A; mu I]: overlapping sources make A numerically rank-deficient by design, and
// mu at 1e-10 of A's scale keeps c bounded without touching the fit. LAPACK (OpenBLAS on Debian)
// factors 5-10x faster than Eigen's own QR; it is serial, so the result is the same on any rank.
Eigen::VectorXcd solve_regularized_least_squares(const Eigen::MatrixXcd& a, const Eigen::VectorXcd& b) {
  const Eigen::Index m = a.rows(), n = a.cols();
  const double mu = 1e-10 * a.norm() / std::sqrt(static_cast<double>(n));
  Eigen::MatrixXcd augmented(m + n, n);  // column-major, as LAPACK wants
  augmented.topRows(m) = a;
  augmented.bottomRows(n) = Eigen::MatrixXcd::Identity(n, n) * mu;
  Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(m + n);
  rhs.head(m) = b;
  const int rows = static_cast<int>(m + n), cols = static_cast<int>(n), one = 1;
  int info = 0, lwork = -1;
  std::complex<double> query;
  zgels_("N", &rows, &cols, &one, augmented.data(), &rows, rhs.data(), &rows, &query, &lwork, &info, 1);
  lwork = static_cast<int>(query.real());
  std::vector<std::complex<double>> work(static_cast<std::size_t>(std::max(lwork, 1)));
  zgels_("N", &rows, &cols, &one, augmented.data(), &rows, rhs.data(), &rows, work.data(), &lwork, &info, 1);
  if (info != 0) throw std::runtime_error("equivalent sources: LAPACK zgels failed, info " + std::to_string(info));
  return rhs.head(n);
}

SourceFit fit_sources(double k_rad_m, const SurfacePoints& fit, const MirroredData& g, const SourceLayout& layout,
                      double class_budget) {
  SourceFit out;
  const auto m = static_cast<Eigen::Index>(fit.size());
  double total = 0;
  for (int s = 0; s < 8; ++s)
    for (std::size_t i = 0; i < fit.size(); ++i) total += fit.weight_m2[i] * g[static_cast<std::size_t>(s)][i] * g[static_cast<std::size_t>(s)][i];
  out.data_norm = std::sqrt(total);
  std::array<Eigen::VectorXcd, 8> rhs;
  std::array<double, 8> norm2{};
  for (int sigma = 0; sigma < 8; ++sigma) {
    // g_sigma(x) = 1/8 sum_s sign(s) g(mirror_s x); ||g||^2 = 8 sum_sigma ||g_sigma||^2 on the octant.
    Eigen::VectorXcd& b = rhs[static_cast<std::size_t>(sigma)];
    b.resize(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      double v = 0;
      for (int s = 0; s < 8; ++s) v += parity_sign(s, sigma) * g[static_cast<std::size_t>(s)][static_cast<std::size_t>(i)];
      v /= 8;
      b(i) = std::sqrt(fit.weight_m2[static_cast<std::size_t>(i)]) * v;
      norm2[static_cast<std::size_t>(sigma)] += 8 * std::norm(b(i));
    }
  }
  // The smallest classes left out first, while together they stay within the budget (the check
  // measures the residual with them).
  std::array<int, 8> by_size{0, 1, 2, 3, 4, 5, 6, 7};
  std::stable_sort(by_size.begin(), by_size.end(), [&](int x, int y) { return norm2[static_cast<std::size_t>(x)] < norm2[static_cast<std::size_t>(y)]; });
  std::vector<int> sigmas;
  double left_out2 = 0;
  for (const int sigma : by_size) {
    const double n2 = norm2[static_cast<std::size_t>(sigma)];
    if (total == 0 || left_out2 + n2 <= class_budget * class_budget * total) left_out2 += n2;
    else sigmas.push_back(sigma);
  }
  std::sort(sigmas.begin(), sigmas.end());
  out.left_out_share = total > 0 ? std::sqrt(left_out2 / total) : 0.0;
  const auto matrices = system_matrices(k_rad_m, fit, layout, sigmas);
  for (std::size_t c = 0; c < sigmas.size(); ++c) {
    const auto& a = matrices[c];
    const auto& b = rhs[static_cast<std::size_t>(sigmas[c])];
    ParityFit pf;
    pf.sigma = sigmas[c];
    pf.strengths = solve_regularized_least_squares(a, b);
    pf.data_norm = std::sqrt(norm2[static_cast<std::size_t>(sigmas[c])]);
    pf.amplification = a.norm() * pf.strengths.norm() / b.norm();
    out.classes.push_back(std::move(pf));
  }
  return out;
}

namespace {

// Per fitted class, the strengths of a level's samples: their unknowns' shares summed.
std::complex<double> sample_strength(const SpreadPoint& sample, const ParityFit& pf) {
  std::complex<double> v = 0;
  for (std::size_t t = 0; t < sample.taps.size(); ++t) v += sample.weight_for(t, pf.sigma) * pf.strengths(sample.taps[t].unknown);
  return v;
}
std::vector<std::complex<double>> sample_strengths(const std::vector<SpreadPoint>& samples, const ParityFit& pf) {
  std::vector<std::complex<double>> out;
  for (const SpreadPoint& sample : samples) out.push_back(sample_strength(sample, pf));
  return out;
}

// Adds to `out` the field of monopoles at `positions` (per class strengths) at the points `which`.
void add_fields(double k, std::span<const Eigen::Vector3d> positions,
                const std::vector<std::vector<std::complex<double>>>& strengths, const SurfacePoints& points,
                const std::vector<std::size_t>& which, FieldParts parts, std::vector<ClassField>& out) {
  const bool pressure = parts == FieldParts::kPressureAndNormalDerivative;
  for (std::size_t j = 0; j < positions.size(); ++j) {
    const auto images = images_of(positions[j]);
    ImageGreens g;
    for (const std::size_t i : which) {
      image_greens(k, points.position_m[i], points.normal[i], images, g);
      for (std::size_t c = 0; c < out.size(); ++c) {
        if (pressure) out[c].pressure[i] += strengths[c][j] * class_sum(g.value_re, g.value_im, out[c].sigma);
        out[c].normal_derivative[i] += strengths[c][j] * class_sum(g.dn_re, g.dn_im, out[c].sigma);
      }
    }
  }
}

}  // namespace

ClassMonopoles class_monopoles(const SourceFit& fit, const SourceLayout& layout) {
  ClassMonopoles out;
  if (layout.spread.empty()) {
    out.position_m = layout.sources.position_m;
    for (const auto& pf : fit.classes) out.strengths.push_back(pf.strengths);
    return out;
  }
  for (const SpreadRow& row : layout.spread)
    for (const SpreadPoint& p : row.levels.front()) out.position_m.push_back(p.position_m);
  for (const auto& pf : fit.classes) {
    Eigen::VectorXcd s(static_cast<Eigen::Index>(out.position_m.size()));
    Eigen::Index at = 0;
    for (const SpreadRow& row : layout.spread)
      for (const auto& v : sample_strengths(row.levels.front(), pf)) s(at++) = v;
    out.strengths.push_back(std::move(s));
  }
  return out;
}

std::vector<ClassField> class_fields(double k_rad_m, const SourceFit& fit, const SourceLayout& layout,
                                     const SurfacePoints& points, FieldParts parts) {
  const std::size_t m = points.size();
  std::vector<ClassField> out;
  for (const auto& pf : fit.classes)
    out.push_back({pf.sigma, std::vector<std::complex<double>>(m), std::vector<std::complex<double>>(m)});
  if (layout.spread.empty()) {
    std::vector<std::size_t> all(m);
    for (std::size_t i = 0; i < m; ++i) all[i] = i;
    std::vector<std::vector<std::complex<double>>> strengths;
    for (const auto& pf : fit.classes) strengths.emplace_back(pf.strengths.data(), pf.strengths.data() + pf.strengths.size());
    add_fields(k_rad_m, layout.sources.position_m, strengths, points, all, parts, out);
    return out;
  }
  // The field of the finest samples, each panel taken as coarsely as level_rule allows: the
  // residual and the far-field checks see the sources the expansion is built from.
  std::vector<std::vector<std::complex<double>>> strengths(fit.classes.size(), std::vector<std::complex<double>>(1));
  for (const SpreadRow& row : layout.spread)
    for_each_sample(row, points, level_rule(k_rad_m), [&](const SpreadPoint& p, const std::vector<std::size_t>& near) {
      for (std::size_t c = 0; c < fit.classes.size(); ++c) strengths[c][0] = sample_strength(p, fit.classes[c]);
      add_fields(k_rad_m, std::span(&p.position_m, 1), strengths, points, near, parts, out);
    });
  return out;
}

double green_evaluations(double k_rad_m, const SourceLayout& layout, const SurfacePoints& fit, const SurfacePoints& check) {
  if (layout.spread.empty()) return static_cast<double>(fit.size() + check.size()) * static_cast<double>(layout.sources.size());
  double total = 0;
  const auto count = [&](const SpreadPoint&, const std::vector<std::size_t>& near) { total += static_cast<double>(near.size()); };
  for (const SpreadRow& row : layout.spread) {
    for_each_sample(row, fit, level_rule(k_rad_m), count);
    for_each_sample(row, check, level_rule(k_rad_m), count);
  }
  return total;
}

void field_at_mirror(const std::vector<ClassField>& fields, int s, std::vector<std::complex<double>>& pressure,
                     std::vector<std::complex<double>>& normal_derivative) {
  const std::size_t m = fields.empty() ? 0 : fields.front().pressure.size();
  pressure.assign(m, 0.0);
  normal_derivative.assign(m, 0.0);
  for (const auto& f : fields) {
    const double sign = parity_sign(s, f.sigma);
    for (std::size_t i = 0; i < m; ++i) {
      pressure[i] += sign * f.pressure[i];
      normal_derivative[i] += sign * f.normal_derivative[i];
    }
  }
}

}  // namespace clatter::kernels::transfer
