// Adaptive direction sets (kernels/pan/direction_mesh.hpp) against the uniform layout they start
// from, polynomials their quadratic elements must reproduce exactly, and a field with one sharp
// lobe whose refinement must stay local (docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "kernels/pan/direction_mesh.hpp"
#include "kernels/pan/directions.hpp"

using namespace clatter::kernels::pan;

namespace {

std::array<double, 3> random_direction(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::array<double, 3> d{u(rng), u(rng), u(rng)};
  if (u(rng) < 0.1) d[static_cast<std::size_t>(rng() % 3)] = 0;  // octant boundaries too
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  return {d[0] / n, d[1] / n, d[2] / n};
}

// A quadratic in the gnomonic coordinates (x, y) / (x + y + z).
double quadratic(const std::array<double, 3>& d) {
  const double s = d[0] + d[1] + d[2], u = d[0] / s, v = d[1] / s;
  return 0.3 + 1.7 * u - 0.9 * v + 2.1 * u * u - 1.3 * u * v + 0.8 * v * v;
}

double interpolate(const DirectionMesh& mesh, const DirectionWeights& w, double (*f)(const std::array<double, 3>&)) {
  double s = 0;
  for (int i = 0; i < w.count; ++i)
    s += w.weight[static_cast<std::size_t>(i)] * f(mesh.direction(static_cast<std::size_t>(w.vertex[static_cast<std::size_t>(i)])));
  return s;
}

}  // namespace

TEST(DirectionMesh, UnrefinedItIsTheUniformLayout) {
  for (int d : {2, 8, 16}) {
    const DirectionMesh mesh(d, 3);
    ASSERT_EQ(mesh.size(), direction_vertices(d).size());
    for (std::size_t v = 0; v < mesh.size(); ++v) EXPECT_EQ(mesh.direction(v), direction_vertices(d)[v]) << d << " " << v;
    EXPECT_EQ(mesh.elements().size(), static_cast<std::size_t>(d * d / 4));
    std::mt19937 rng(d);
    for (int i = 0; i < 2000; ++i) {
      const auto x = random_direction(rng);
      const DirectionWeights a = mesh.locate(x), b = locate_direction(x, d, Interpolation::quadratic);
      ASSERT_EQ(a.count, b.count);
      for (std::size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(a.vertex[k], b.vertex[k]);
        EXPECT_NEAR(a.weight[k], b.weight[k], 1e-12);
      }
      // Linear: the same triangle of the layout (its corners in another order), the same weights.
      const DirectionWeights la = locate(d, mesh.stored(), x, Interpolation::linear);
      const DirectionWeights lb = locate_direction(x, d, Interpolation::linear);
      ASSERT_EQ(la.count, 3);
      ASSERT_EQ(lb.count, 3);
      for (std::size_t k = 0; k < 3; ++k) {
        double w = 0;
        for (std::size_t j = 0; j < 3; ++j)
          if (la.vertex[j] == lb.vertex[k]) w += la.weight[j];
        EXPECT_NEAR(w, lb.weight[k], 1e-12) << x[0] << " " << x[1] << " " << x[2];
      }
    }
  }
}

TEST(DirectionMesh, TheLayoutBuiltFromTheTwoDivisionRootIsTheSameLayout) {
  // A bank's sets start from the 2-division octant split uniformly (uniform_mesh): the same
  // directions and the same quadratic interpolant as the layout itself, numbered root first.
  for (int d : {2, 4, 8, 16}) {
    const DirectionMesh layout(d, 2), tree = uniform_mesh(d, 2);
    EXPECT_EQ(tree.divisions(), 2);
    ASSERT_EQ(tree.size(), layout.size());
    for (std::size_t v = 0; v < tree.size(); ++v) {
      bool found = false;
      for (std::size_t w = 0; w < layout.size() && !found; ++w) found = tree.vertices()[v] == layout.vertices()[w];
      EXPECT_TRUE(found) << d << " " << v;
    }
    std::mt19937 rng(d);
    auto wiggly = [](const std::array<double, 3>& x) { return std::sin(5 * x[0]) + std::cos(7 * x[1] * x[2]); };
    for (int i = 0; i < 500; ++i) {
      const auto x = random_direction(rng);
      EXPECT_NEAR(interpolate(tree, tree.locate(x), wiggly), interpolate(layout, layout.locate(x), wiggly), 1e-12) << d;
    }
  }
  EXPECT_THROW(uniform_mesh(12, 1), std::invalid_argument);
}

TEST(DirectionMesh, RefinedItReproducesQuadraticsAndSharesVertices) {
  DirectionMesh mesh(8, 4);
  std::mt19937 rng(7);
  for (int i = 0; i < 60; ++i) {  // random splits of random leaves, down to the deepest level
    const std::size_t e = rng() % mesh.elements().size();
    if (mesh.can_split(e)) mesh.split(e);
  }
  int deepest = 0;
  for (std::size_t e = 0; e < mesh.elements().size(); ++e) deepest = std::max(deepest, mesh.level(e));
  EXPECT_GE(deepest, 2);
  // Every vertex once: no two at one direction.
  for (std::size_t v = 0; v < mesh.size(); ++v)
    for (std::size_t w = v + 1; w < mesh.size(); ++w) ASSERT_FALSE(mesh.vertices()[v] == mesh.vertices()[w]);
  for (int i = 0; i < 4000; ++i) {
    const auto x = random_direction(rng);
    const DirectionWeights w = mesh.locate(x);
    double sum = 0;
    for (double v : w.weight) sum += v;
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_NEAR(interpolate(mesh, w, quadratic), quadratic(x), 1e-12);
  }
}

TEST(DirectionMesh, StoredArraysRoundTripAndWrongOnesAreRefused) {
  DirectionMesh mesh(8, 3);
  mesh.split(5);
  mesh.split(2);
  mesh.split(static_cast<std::size_t>(mesh.first_child()[5] + 3));  // a centre child
  const DirectionMesh copy(8, 3, mesh.stored());
  EXPECT_EQ(copy.vertices(), mesh.vertices());
  EXPECT_EQ(copy.elements(), mesh.elements());
  auto changed = [&](auto&& change) {
    clatter::model::PanDirections set = mesh.stored();
    change(set);
    return set;
  };
  EXPECT_THROW(DirectionMesh(8, 3, changed([](auto& s) { s.vertices[50].a += 1; })), std::invalid_argument);
  // a root as its own... children
  EXPECT_THROW(DirectionMesh(8, 3, changed([](auto& s) { s.first_child[0] = 3; })), std::invalid_argument);
  EXPECT_THROW(DirectionMesh(8, 3, changed([](auto& s) { std::swap(s.elements[20][0], s.elements[20][1]); })),
               std::invalid_argument);
  EXPECT_THROW(DirectionMesh(8, 3, changed([](auto& s) { s.first_child.clear(); })), std::invalid_argument);
  EXPECT_THROW(DirectionMesh(8, 2, mesh.stored()), std::invalid_argument);  // another lattice
  EXPECT_THROW(DirectionMesh(7, 3), std::invalid_argument);
}

namespace {
// A directivity with one sharp lobe (about 6 degrees wide) on a smooth background: what an
// elongated proxy's far field looks like, in one number per direction.
double lobe(const std::array<double, 3>& d) {
  const std::array<double, 3> axis{0.8, 0.36, 0.48};
  const double c = d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2];
  return 0.2 + 0.3 * d[2] + std::exp(-(1 - c) / 0.006);
}
}  // namespace

TEST(DirectionMesh, RefinementFollowsASharpLobeAndStaysLocal) {
  const double tolerance = 0.005;
  DirectionMesh mesh(8, 4);
  auto miss = [&](const LatticePoint& p, const DirectionWeights& w) { return std::abs(interpolate(mesh, w, lobe) - lobe(mesh.direction(p))); };
  const int splits = refine(mesh, miss, tolerance, 10000);
  // The worst miss at random directions, refined against uniform layouts.
  std::mt19937 rng(3);
  auto worst = [&](auto&& at) {
    double e = 0;
    for (int i = 0; i < 20000; ++i) {
      const auto x = random_direction(rng);
      e = std::max(e, std::abs(at(x) - lobe(x)));
    }
    return e;
  };
  const double refined = worst([&](const std::array<double, 3>& x) { return interpolate(mesh, mesh.locate(x), lobe); });
  const DirectionMesh uniform(32, 0);
  const double uniform_miss = worst([&](const std::array<double, 3>& x) { return interpolate(uniform, uniform.locate(x), lobe); });
  std::printf("sharp lobe: %d splits, %zu directions, worst miss %.3g (tolerance %.3g); uniform, 32 divisions: %zu "
              "directions, worst miss %.3g\n", splits, mesh.size(), refined, tolerance, uniform.size(), uniform_miss);
  // The lobe is resolved to about the tolerance (the split points are samples, not a bound: a
  // margin of 3), with fewer directions than the uniform layout that misses it 5x as far.
  EXPECT_LT(refined, 3 * tolerance);
  EXPECT_LT(mesh.size(), uniform.size());
  EXPECT_GT(uniform_miss, 5 * refined);
  // Local: the elements far from the lobe (the octant's other corners) were not split.
  const DirectionWeights far = mesh.locate({0.02, 0.97, 0.05});
  for (std::size_t e = 0; e < mesh.elements().size(); ++e) {
    if (mesh.elements()[e][0] == far.vertex[0] && mesh.first_child()[e] < 0) {
      EXPECT_EQ(mesh.level(e), 0);
    }
  }
}
