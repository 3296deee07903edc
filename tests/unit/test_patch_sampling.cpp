// The soundbank's patch sampling (kernels/modal/patch_sampling.*): the log-ratio parameterization,
// the patch-point check, and the adaptive triangulation against synthetic features whose relative
// change along an edge is known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <string>

#include "kernels/modal/patch_sampling.hpp"

namespace {
using namespace clatter::kernels::modal;
using Features = std::vector<std::vector<double>>;
using Edge = std::pair<int, int>;

// A feature function from a per-ellipsoid formula.
template <class F>
FeatureBatch batch_of(F f) {
  return [f](const std::vector<Axes>& axes) {
    Features out;
    for (const auto& x : axes) out.push_back(f(x));
    return out;
  };
}

// Powers of the ratios: ln f = -(u + v) and -u/2, so along an edge (du, dv) the relative change is
// exp(max(|du + dv|, |du| / 2)) - 1, whatever the edge's place.
std::vector<double> power_law(const Axes& x) { return {x[2] / x[0], std::sqrt(x[2] / x[1])}; }
// A pole just past the cigar (pancake) corner: d ln f / du = -(1/4) (b/c) / (b/c - 0.9 r) is -2.5 at
// the corner but about -0.27 near the sphere, so the edges must shrink toward that corner only.
std::vector<double> cigar_pole(const Axes& x) { return {std::pow(x[1] / x[2] - 0.09, -0.25)}; }
std::vector<double> pancake_pole(const Axes& x) { return {std::pow(x[0] / x[1] - 0.09, -0.25)}; }
// The brief's example: large toward small a/c (both thin corners), but close to a power law in logs.
std::vector<double> thin_blowup(const Axes& x) { return {1 / (x[0] / x[2] + 0.02)}; }

const double kLogR = std::log(0.1);

std::map<Edge, int> edge_counts(const PatchSampling& s) {
  std::map<Edge, int> count;
  for (const auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(t[k], t[(k + 1) % 3])];
  return count;
}

// On the patch's boundary: u = 0, v = 0, or the edge u / ln r_c + v / ln r = 1 from the cigar to
// the pancake.
bool on_boundary(const std::array<double, 2>& p, const std::array<double, 2>& q, const PatchCorners& corners) {
  auto near = [](double x, double y) { return std::abs(x - y) < 1e-9; };
  const double lc = std::log(corners.cigar_ratio), lr = std::log(corners.min_ratio);
  return (near(p[0], 0) && near(q[0], 0)) || (near(p[1], 0) && near(q[1], 0)) ||
         (near(p[0] / lc + p[1] / lr, 1) && near(q[0] / lc + q[1] / lr, 1));
}

// Conforming: every edge on the patch boundary in one triangle, every other in two; all triangles
// counter-clockwise; their areas sum to the patch triangle's, ln r_c ln r / 2.
void expect_conforming(const PatchSampling& s, const PatchCorners& corners = {}) {
  for (const auto& [e, count] : edge_counts(s)) {
    const bool boundary = on_boundary(log_ratios(s.samples[e.first]), log_ratios(s.samples[e.second]), corners);
    EXPECT_EQ(count, boundary ? 1 : 2) << "edge " << e.first << "-" << e.second;
  }
  double area = 0;
  for (const auto& t : s.triangles) {
    const auto p = log_ratios(s.samples[t[0]]), q = log_ratios(s.samples[t[1]]), r = log_ratios(s.samples[t[2]]);
    const double twice = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
    EXPECT_GT(twice, 0);
    area += twice / 2;
  }
  EXPECT_NEAR(area, std::log(corners.cigar_ratio) * std::log(corners.min_ratio) / 2, 1e-10);
}

// The criterion on every final edge: the reported worst change and count are the edges' own, and
// edges stay over tolerance only when the last level allowed was used.
void expect_criterion(const PatchSampling& s, const PatchSamplingSettings& settings) {
  double worst = 0;
  int over = 0;
  for (const auto& [e, count] : edge_counts(s)) {
    const double change = relative_change(s.features[e.first], s.features[e.second]);
    worst = std::max(worst, change);
    over += change > settings.tolerance;
  }
  EXPECT_EQ(s.worst_change, worst);
  EXPECT_EQ(s.edges_over_tolerance, over);
  if (over > 0) {
    EXPECT_EQ(*std::max_element(s.level.begin(), s.level.end()), settings.max_level);
  } else {
    EXPECT_LE(worst, settings.tolerance);
  }
}

void expect_patch_points(const PatchSampling& s, const PatchCorners& corners) {
  std::set<Axes> unique(s.samples.begin(), s.samples.end());
  EXPECT_EQ(unique.size(), s.samples.size());
  ASSERT_EQ(s.features.size(), s.samples.size());
  ASSERT_EQ(s.level.size(), s.samples.size());
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const auto& x = s.samples[i];
    EXPECT_EQ(patch_violation(x, corners), "") << "sample " << i;
    EXPECT_NEAR(x[0] * x[0] + x[1] * x[1] + x[2] * x[2], 1, 1e-12);
    if (i > 0) {
      EXPECT_LE(s.level[i - 1], s.level[i]);
    }
  }
}

// Largest and mean sample level within log-distance `radius` of the corner (u, v).
std::pair<int, double> levels_near(const PatchSampling& s, double u, double v, double radius) {
  int top = 0, n = 0;
  double sum = 0;
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const auto p = log_ratios(s.samples[i]);
    if (std::hypot(p[0] - u, p[1] - v) > radius) continue;
    top = std::max(top, s.level[i]);
    sum += s.level[i];
    ++n;
  }
  return {top, n ? sum / n : 0};
}

TEST(PatchSampling, LogRatiosRoundTripAndCorners) {
  for (double u : {0.0, -0.3, -1.7})
    for (double v : {0.0, -0.01, -2.2}) {
      const Axes x = axes_from_log_ratios(u, v);
      EXPECT_NEAR(x[0] * x[0] + x[1] * x[1] + x[2] * x[2], 1, 1e-14);
      const auto back = log_ratios(x);
      EXPECT_NEAR(back[0], u, 1e-14);
      EXPECT_NEAR(back[1], v, 1e-14);
    }
  const double r = 0.1;
  const Axes sphere = axes_from_log_ratios(0, 0);
  for (double x : sphere) EXPECT_NEAR(x, 1 / std::sqrt(3.0), 1e-15);
  const Axes pancake = axes_from_log_ratios(0, std::log(r));
  EXPECT_EQ(pancake[1], pancake[2]);
  EXPECT_NEAR(pancake[0], r * pancake[1], 1e-15);
  EXPECT_NEAR(pancake[2], 1 / std::sqrt(2 + r * r), 1e-15);
  const Axes cigar = axes_from_log_ratios(std::log(r), 0);
  EXPECT_EQ(cigar[0], cigar[1]);
  EXPECT_NEAR(cigar[1], r * cigar[2], 1e-15);
  for (const auto& x : {sphere, pancake, cigar}) EXPECT_EQ(patch_violation(x, {r, r}), "");
  EXPECT_THROW(axes_from_log_ratios(0.1, 0), std::invalid_argument);
  EXPECT_THROW(axes_from_log_ratios(0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(log_ratios({0, 1, 1}), std::invalid_argument);
}

TEST(PatchSampling, ViolationNamesTheProblem) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), s3 = 1 / std::sqrt(3.0);
  auto has = [](const std::string& message, const char* word) {
    return message.find(word) != std::string::npos;
  };
  EXPECT_TRUE(has(patch_violation({-0.1, 0.5, 0.86}, {0.1, 0.1}), "not positive"));
  EXPECT_TRUE(has(patch_violation({0, 0.5, 0.86}, {0.1, 0.1}), "not positive"));
  EXPECT_TRUE(has(patch_violation({s3, nan, s3}, {0.1, 0.1}), "not finite"));
  EXPECT_TRUE(has(patch_violation({0.6, 0.5, 0.62449979983983983}, {0.1, 0.1}), "not ascending"));
  EXPECT_TRUE(has(patch_violation({0.5, 0.6, 0.7}, {0.1, 0.1}), "unit sphere"));
  const Axes thin = axes_from_log_ratios(std::log(0.2), std::log(0.4));  // a/c = 0.08
  EXPECT_TRUE(has(patch_violation(thin, {0.1, 0.1}), "below min_ratio"));
  EXPECT_EQ(patch_violation(thin, {0.08, 0.08}), "");
  EXPECT_EQ(patch_violation({s3, s3, s3}, {0.1, 0.1}), "");
  EXPECT_THROW(patch_violation({s3, s3, s3}, {0, 0}), std::invalid_argument);
}

// A patch whose cigar is blunter than its pancake (b/c = 0.1 there, a/c = 0.025 at the pancake):
// the corners are where they are asked, the edge between them is the patch's (its midpoint in
// log ratios inside, a step past it outside, which a/c alone cannot tell: the step's a/c is above
// 0.025), and the sampling triangulates exactly that triangle.
TEST(PatchSampling, TwoCornersMakeTheTriangleBetweenThem) {
  const PatchCorners corners{0.025, 0.1};
  const double lr = std::log(corners.min_ratio), lc = std::log(corners.cigar_ratio);
  const Axes cigar = axes_from_log_ratios(lc, 0), pancake = axes_from_log_ratios(0, lr);
  EXPECT_NEAR(cigar[1] / cigar[2], 0.1, 1e-15);
  EXPECT_NEAR(pancake[0] / pancake[2], 0.025, 1e-15);
  const Axes middle = axes_from_log_ratios(lc / 2, lr / 2);  // a/c = sqrt(0.1 x 0.025) = 0.05
  EXPECT_NEAR(middle[0] / middle[2], 0.05, 1e-15);
  const Axes beyond = axes_from_log_ratios(0.55 * lc, 0.55 * lr);  // a/c = 0.037
  for (const auto& x : {cigar, pancake, middle}) EXPECT_EQ(patch_violation(x, corners), "");
  EXPECT_NE(patch_violation(beyond, corners).find("beyond the patch's edge from the cigar"), std::string::npos)
      << patch_violation(beyond, corners);
  EXPECT_EQ(patch_violation(beyond, {0.025, 0.025}), "");  // equal corners: a/c >= 0.025 only
  EXPECT_NE(patch_violation(cigar, {0.025, 0.2}), "");      // a cigar blunter than this one's
  EXPECT_THROW(patch_violation(cigar, {0.1, 0.05}), std::invalid_argument);
  EXPECT_NE(corners_violation({0.1, 0.05}).find("cigar_ratio must be in [min_ratio, 1)"), std::string::npos);

  PatchSamplingSettings settings;
  settings.corners = corners;
  const auto s = sample_patch(settings, batch_of(power_law));
  expect_patch_points(s, corners);
  expect_conforming(s, corners);
  expect_criterion(s, settings);
  std::set<Axes> samples(s.samples.begin(), s.samples.end());
  EXPECT_TRUE(samples.count(cigar) && samples.count(pancake) && samples.count(axes_from_log_ratios(0, 0)));
}

// NVB's grids are criss-cross: after k levels of uniform refinement the legs are h / 2^k (h =
// |ln r| / 2, the level-0 leg) along u and v, and the hypotenuses run along both diagonals. With
// the power law the worst edges are the (1, 1) diagonals, du + dv = 2 h / 2^k: change
// exp(2 h / 2^k) - 1, within 0.1 only for 2^k >= 24.2. Axis legs and (1, -1) diagonals change by
// exp(h / 2^k) - 1 and exp(h / 2^(k+1)) - 1, within 0.1 from 2^k >= 12.1, so every edge is split
// at levels 1..4 and level 5 splits only the (1, 1) diagonals.
TEST(PatchSampling, PowerLawMeetsToleranceWithKnownChanges) {
  PatchSamplingSettings settings;
  settings.max_level = 5;
  const auto s = sample_patch(settings, batch_of(power_law));
  expect_patch_points(s, settings.corners);
  expect_conforming(s);
  expect_criterion(s, settings);
  for (const auto& [e, count] : edge_counts(s)) {
    const auto p = log_ratios(s.samples[e.first]), q = log_ratios(s.samples[e.second]);
    const double du = q[0] - p[0], dv = q[1] - p[1];
    const double expected = std::exp(std::max(std::abs(du + dv), std::abs(du) / 2)) - 1;
    EXPECT_NEAR(relative_change(s.features[e.first], s.features[e.second]), expected, 1e-12);
  }
  const double h = -kLogR / 2;
  EXPECT_LE(s.worst_change, settings.tolerance);
  EXPECT_EQ(s.edges_over_tolerance, 0);
  EXPECT_NEAR(s.worst_change, std::exp(h / 16) - 1, 1e-12);
  // The uniform 32-division grid, 33 * 34 / 2 points, plus one midpoint per (1, 1) diagonal.
  EXPECT_EQ(s.samples.size(), 33u * 34u / 2u + 256u);
  EXPECT_EQ(*std::max_element(s.level.begin(), s.level.end()), 5);
}

TEST(PatchSampling, MaxLevelLeavesEdgesOverTolerance) {
  const PatchSamplingSettings settings;  // max_level 4: the (1, 1) diagonals above stay over
  const auto s = sample_patch(settings, batch_of(power_law));
  expect_conforming(s);
  expect_criterion(s, settings);
  const double h = -kLogR / 2;
  EXPECT_NEAR(s.worst_change, std::exp(2 * h / 16) - 1, 1e-12);
  EXPECT_EQ(s.edges_over_tolerance, 256);
  EXPECT_EQ(s.samples.size(), 33u * 34u / 2u);
  EXPECT_EQ(s.triangles.size(), 32u * 32u);
  EXPECT_EQ(*std::max_element(s.level.begin(), s.level.end()), settings.max_level);
}

TEST(PatchSampling, StopsWhenWithinTolerance) {
  PatchSamplingSettings settings;
  settings.tolerance = 3;  // the level-0 legs change by exp(|ln r| / 2) - 1 = 2.16
  int calls = 0;
  const auto counted = [&](const std::vector<Axes>& axes) {
    ++calls;
    return batch_of(power_law)(axes);
  };
  const auto s = sample_patch(settings, counted);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(s.samples.size(), 6u);
  EXPECT_EQ(s.triangles.size(), 4u);
  EXPECT_NEAR(s.worst_change, std::exp(-kLogR / 2) - 1, 1e-12);
  expect_conforming(s);
  expect_criterion(s, settings);
}

TEST(PatchSampling, RefinesTowardTheFastCorner) {
  const PatchSamplingSettings settings;
  for (bool cigar : {true, false}) {
    const auto s = sample_patch(settings, batch_of(cigar ? cigar_pole : pancake_pole));
    expect_patch_points(s, settings.corners);
    expect_conforming(s);
    expect_criterion(s, settings);
    const auto at_cigar = levels_near(s, kLogR, 0, 0.6), at_pancake = levels_near(s, 0, kLogR, 0.6);
    const auto& fast = cigar ? at_cigar : at_pancake;
    const auto& slow = cigar ? at_pancake : at_cigar;
    EXPECT_EQ(fast.first, settings.max_level);
    EXPECT_LT(slow.first, fast.first);
    EXPECT_GT(fast.second, slow.second + 1);
    std::printf("%s pole: %zu samples, level near it max %d mean %.2f, at the other corner max %d mean %.2f, "
                "worst change %.3f, %d edges over\n",
                cigar ? "cigar" : "pancake", s.samples.size(), fast.first, fast.second, slow.first, slow.second,
                s.worst_change, s.edges_over_tolerance);
  }
}

TEST(PatchSampling, BatchesAreTheNewPointsOfEachLevel) {
  std::vector<std::size_t> sizes;
  const auto recorded = [&](const std::vector<Axes>& axes) {
    sizes.push_back(axes.size());
    return batch_of(cigar_pole)(axes);
  };
  const auto s = sample_patch({}, recorded);
  std::vector<std::size_t> per_level(sizes.size(), 0);
  for (int l : s.level) ++per_level.at(l);
  EXPECT_EQ(per_level, sizes);
}

TEST(PatchSampling, Deterministic) {
  const auto a = sample_patch({}, batch_of(cigar_pole)), b = sample_patch({}, batch_of(cigar_pole));
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.features, b.features);
  EXPECT_EQ(a.level, b.level);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.worst_change, b.worst_change);
  EXPECT_EQ(a.edges_over_tolerance, b.edges_over_tolerance);
}

TEST(PatchSampling, RejectsBadSettingsAndFeatures) {
  auto with = [](auto change) {
    PatchSamplingSettings s;
    change(s);
    return s;
  };
  const auto f = batch_of(power_law);
  EXPECT_THROW(sample_patch(with([](auto& s) { s.corners.min_ratio = 1; }), f), std::invalid_argument);
  EXPECT_THROW(sample_patch(with([](auto& s) { s.initial_divisions = 0; }), f), std::invalid_argument);
  EXPECT_THROW(sample_patch(with([](auto& s) { s.tolerance = 0; }), f), std::invalid_argument);
  EXPECT_THROW(sample_patch(with([](auto& s) { s.max_level = 17; }), f), std::invalid_argument);
  EXPECT_THROW(sample_patch({}, batch_of([](const Axes&) { return std::vector<double>{-1}; })), std::runtime_error);
  EXPECT_THROW(sample_patch({}, [](const std::vector<Axes>&) { return Features{}; }), std::runtime_error);
  EXPECT_THROW(relative_change({1, 2}, {1}), std::invalid_argument);
}

TEST(PatchSampling, SampleCountsWithDefaults) {
  const std::pair<const char*, std::vector<double> (*)(const Axes&)> cases[] = {
      {"power law {c/a, sqrt(c/b)}", power_law},
      {"cigar pole (b/c - 0.09)^-1/4", cigar_pole},
      {"pancake pole (a/b - 0.09)^-1/4", pancake_pole},
      {"1/(a/c + 0.02)", thin_blowup}};
  for (int max_level : {4, 6})
    for (const auto& [name, formula] : cases) {
      PatchSamplingSettings settings;
      settings.max_level = max_level;
      const auto s = sample_patch(settings, batch_of(formula));
      expect_patch_points(s, settings.corners);
      expect_conforming(s);
      expect_criterion(s, settings);
      const int top = *std::max_element(s.level.begin(), s.level.end());
      std::printf("max_level %d, %-31s %5zu samples, %5zu triangles, top level %d, worst change %.4f, %d edges over\n",
                  max_level, name, s.samples.size(), s.triangles.size(), top, s.worst_change,
                  s.edges_over_tolerance);
    }
}

}  // namespace
