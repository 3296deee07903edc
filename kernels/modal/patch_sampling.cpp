// Adaptive sampling of the ellipsoid patch by newest-vertex bisection in log-ratio coordinates
// (the header says why logs and why NVB).
#include "kernels/modal/patch_sampling.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace clatter::kernels::modal {
namespace {

// Integer coordinates (i, j) on the initial grid refined 2^max_level times: u = ln r_c * i / N,
// v = ln r * j / N with N = initial_divisions * 2^max_level; the patch is i, j >= 0, i + j <= N.
using Lattice = std::array<int, 2>;
using Edge = std::pair<int, int>;  // sample indices, first < second
// Newest vertex first: the refinement edge is {t[1], t[2]}, the one opposite it.
using Triangle = std::array<int, 3>;

constexpr int kMaxDivisions = 4096, kMaxLevel = 16;  // N <= 2^28: lattice sums stay in int

Edge edge_of(int p, int q) { return p < q ? Edge{p, q} : Edge{q, p}; }

// The shortest text that reads back as x (what the user wrote, for a value from a config).
std::string number(double x) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, x).ptr;
  return std::string(text, end);
}

void check_settings(const PatchSamplingSettings& s) {
  if (const std::string why = corners_violation(s.corners); !why.empty())
    throw std::invalid_argument("patch sampling: " + why);
  if (s.initial_divisions < 1 || s.initial_divisions > kMaxDivisions)
    throw std::invalid_argument("patch sampling: initial_divisions must be in [1, 4096], got " +
                                std::to_string(s.initial_divisions));
  if (!(s.tolerance > 0) || !std::isfinite(s.tolerance))
    throw std::invalid_argument("patch sampling: tolerance must be finite and positive, got " + number(s.tolerance));
  if (s.max_level < 0 || s.max_level > kMaxLevel)
    throw std::invalid_argument("patch sampling: max_level must be in [0, 16], got " + std::to_string(s.max_level));
}

class Sampler {
 public:
  Sampler(const PatchSamplingSettings& settings, const FeatureBatch& features)
      : settings_(settings),
        features_(features),
        lattice_n_(settings.initial_divisions * (1 << settings.max_level)),
        log_cigar_ratio_(std::log(settings.corners.cigar_ratio)),
        log_min_ratio_(std::log(settings.corners.min_ratio)) {}

  PatchSampling run() {
    initial_grid();
    for (int level = 1; level <= settings_.max_level; ++level)
      if (!refine(level)) break;
    for (const auto& [edge, change] : edge_changes()) {
      out_.worst_change = std::max(out_.worst_change, change);
      if (change > settings_.tolerance) ++out_.edges_over_tolerance;
    }
    out_.triangles = triangles_;
    return std::move(out_);
  }

 private:
  // The sample at lattice point p, created (at `level`) only if no sample is there yet.
  int point(const Lattice& p, int level) {
    auto [it, inserted] = index_of_.try_emplace(p, static_cast<int>(lattice_.size()));
    if (inserted) {
      lattice_.push_back(p);
      out_.samples.push_back(axes_from_log_ratios(log_cigar_ratio_ * p[0] / lattice_n_, log_min_ratio_ * p[1] / lattice_n_));
      out_.level.push_back(level);
    }
    return it->second;
  }

  // Right isosceles triangles, the right angle (the newest vertex) first, counter-clockwise.
  void initial_grid() {
    const int n = settings_.initial_divisions, step = lattice_n_ / n;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i + j <= n; ++i) point({i * step, j * step}, 0);
    auto at = [&](int i, int j) { return index_of_.at({i * step, j * step}); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i + j < n; ++i) {
        triangles_.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 2 <= n) triangles_.push_back({at(i + 1, j + 1), at(i, j + 1), at(i + 1, j)});
      }
    evaluate_from(0);
  }

  // Features of samples[first..] in one call of the caller's batch function, checked.
  void evaluate_from(std::size_t first) {
    const std::vector<Axes> batch(out_.samples.begin() + static_cast<std::ptrdiff_t>(first), out_.samples.end());
    auto values = features_(batch);
    if (values.size() != batch.size())
      throw std::runtime_error("patch sampling: the feature function returned " + std::to_string(values.size()) +
                               " vectors for " + std::to_string(batch.size()) + " ellipsoids");
    for (auto& f : values) {
      if (feature_count_ == 0) feature_count_ = f.size();
      if (f.empty() || f.size() != feature_count_)
        throw std::runtime_error("patch sampling: feature vectors must all have the same, nonzero length (got " +
                                 std::to_string(f.size()) + " after " + std::to_string(feature_count_) + ")");
      for (double x : f)
        if (!(x > 0) || !std::isfinite(x))
          throw std::runtime_error("patch sampling: features must be finite and positive, got " + number(x));
      out_.features.push_back(std::move(f));
    }
  }

  std::map<Edge, double> edge_changes() const {
    std::map<Edge, double> changes;
    for (const auto& t : triangles_)
      for (int k = 0; k < 3; ++k) {
        const Edge e = edge_of(t[k], t[(k + 1) % 3]);
        if (!changes.contains(e)) changes[e] = relative_change(out_.features[e.first], out_.features[e.second]);
      }
    return changes;
  }

  // The marked edges plus, repeated to a fixed point, the refinement edge of every triangle that
  // has a marked edge (so each marked edge gets split by at most two bisections of a triangle).
  void close(std::set<Edge>& marked) const {
    for (bool grew = true; grew;) {
      grew = false;
      for (const auto& t : triangles_) {
        const bool any = marked.contains(edge_of(t[0], t[1])) || marked.contains(edge_of(t[1], t[2])) ||
                         marked.contains(edge_of(t[2], t[0]));
        if (any && marked.insert(edge_of(t[1], t[2])).second) grew = true;
      }
    }
  }

  // One level: false when no edge is over tolerance (nothing to do).
  bool refine(int level) {
    std::set<Edge> marked;
    for (const auto& [edge, change] : edge_changes())
      if (change > settings_.tolerance) marked.insert(edge);
    if (marked.empty()) return false;
    close(marked);
    const std::size_t first = out_.samples.size();
    std::map<Edge, int> midpoint;
    for (const auto& e : marked) {
      const Lattice &p = lattice_[e.first], &q = lattice_[e.second];
      const Lattice sum{p[0] + q[0], p[1] + q[1]};
      // Cannot happen within max_level levels (two bisections halve the legs); a guard, not a case.
      if (sum[0] % 2 != 0 || sum[1] % 2 != 0) throw std::logic_error("patch sampling: midpoint off the lattice");
      midpoint[e] = point({sum[0] / 2, sum[1] / 2}, level);
    }
    evaluate_from(first);
    std::vector<Triangle> refined;
    for (const auto& t : triangles_) bisect(t, midpoint, refined);
    triangles_ = std::move(refined);
    return true;
  }

  // Bisection on the refinement edge keeps the orientation: both children run the parent's way.
  static void bisect(const Triangle& t, const std::map<Edge, int>& midpoint, std::vector<Triangle>& out) {
    const auto it = midpoint.find(edge_of(t[1], t[2]));
    if (it == midpoint.end()) {
      out.push_back(t);
      return;
    }
    bisect({it->second, t[2], t[0]}, midpoint, out);
    bisect({it->second, t[0], t[1]}, midpoint, out);
  }

  const PatchSamplingSettings& settings_;
  const FeatureBatch& features_;
  const int lattice_n_;
  const double log_cigar_ratio_, log_min_ratio_;
  PatchSampling out_;
  std::vector<Lattice> lattice_;  // per sample
  std::map<Lattice, int> index_of_;
  std::vector<Triangle> triangles_;
  std::size_t feature_count_ = 0;
};

}  // namespace

Axes axes_from_log_ratios(double u, double v) {
  if (!std::isfinite(u) || !std::isfinite(v) || u > 0 || v > 0)
    throw std::invalid_argument("axes_from_log_ratios: u = " + number(u) + ", v = " + number(v) +
                                " (both must be finite and <= 0)");
  const double b_over_c = std::exp(u), a_over_c = b_over_c * std::exp(v);
  const double c_m = 1 / std::sqrt(1 + b_over_c * b_over_c + a_over_c * a_over_c);
  const double b_m = c_m * b_over_c;
  return {b_m * std::exp(v), b_m, c_m};
}

std::array<double, 2> log_ratios(const Axes& axes) {
  for (double x : axes)
    if (!(x > 0) || !std::isfinite(x)) throw std::invalid_argument("log_ratios: axes must be finite and positive");
  return {std::log(axes[1] / axes[2]), std::log(axes[0] / axes[1])};
}

std::string corners_violation(const PatchCorners& corners) {
  if (!(corners.min_ratio > 0 && corners.min_ratio < 1)) return "min_ratio must be in (0, 1), got " + number(corners.min_ratio);
  if (!(corners.cigar_ratio >= corners.min_ratio && corners.cigar_ratio < 1))
    return "cigar_ratio must be in [min_ratio, 1) = [" + number(corners.min_ratio) + ", 1), got " +
           number(corners.cigar_ratio);
  return {};
}

std::string patch_violation(const Axes& axes, const PatchCorners& corners, double tolerance) {
  if (const std::string why = corners_violation(corners); !why.empty())
    throw std::invalid_argument("patch_violation: " + why);
  static constexpr const char* kName[3] = {"a", "b", "c"};
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(axes[k])) return std::string("axis ") + kName[k] + " is not finite (" + number(axes[k]) + ")";
    if (!(axes[k] > 0)) return std::string("axis ") + kName[k] + " is not positive (" + number(axes[k]) + ")";
  }
  const auto [a_m, b_m, c_m] = axes;
  if (a_m > b_m * (1 + tolerance) || b_m > c_m * (1 + tolerance))
    return "axes not ascending (a <= b <= c): " + number(a_m) + ", " + number(b_m) + ", " + number(c_m);
  const double norm2 = a_m * a_m + b_m * b_m + c_m * c_m;
  if (std::abs(norm2 - 1) > tolerance) return "off the unit sphere: a^2 + b^2 + c^2 = " + number(norm2);
  if (a_m / c_m < corners.min_ratio * (1 - tolerance))
    return "a/c = " + number(a_m / c_m) + " below min_ratio " + number(corners.min_ratio);
  // The edge from the cigar to the pancake; with equal corners it is the line a/c = min_ratio above.
  if (std::log(b_m / c_m) / std::log(corners.cigar_ratio) + std::log(a_m / b_m) / std::log(corners.min_ratio) >
      1 + tolerance)
    return "b/c = " + number(b_m / c_m) + ", a/c = " + number(a_m / c_m) + " beyond the patch's edge from the cigar (b/c = " +
           number(corners.cigar_ratio) + ") to the pancake (a/c = " + number(corners.min_ratio) + ")";
  return {};
}

PatchSampling sample_patch(const PatchSamplingSettings& settings, const FeatureBatch& features) {
  check_settings(settings);
  if (!features) throw std::invalid_argument("patch sampling: no feature function");
  return Sampler(settings, features).run();
}

double relative_change(const std::vector<double>& f, const std::vector<double>& g) {
  if (f.size() != g.size())
    throw std::invalid_argument("relative_change: " + std::to_string(f.size()) + " features against " +
                                std::to_string(g.size()));
  double worst = 0;
  for (std::size_t k = 0; k < f.size(); ++k) worst = std::max(worst, std::abs(f[k] - g[k]) / std::min(f[k], g[k]));
  return worst;
}

}  // namespace clatter::kernels::modal
