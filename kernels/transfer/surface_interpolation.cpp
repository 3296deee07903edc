#include "kernels/transfer/surface_interpolation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace clatter::kernels::transfer {
namespace {

// Faces bucketed by the cells of a uniform grid over [-1, 1]^3 that their unit-sphere corner
// images' bounding boxes touch, each box grown by the face's own longest edge (the spherical
// patch bulges past the flat corners' box by its sagitta, less than an edge). Cells of the median
// edge: a thin body's rim faces are long on the sphere, and cells of the longest edge put
// thousands of faces in each bucket.
class FaceGrid {
 public:
  FaceGrid(const std::vector<std::array<Eigen::Vector3d, 3>>& corners) {
    std::vector<double> sizes(corners.size());
    for (std::size_t f = 0; f < corners.size(); ++f)
      for (int k = 0; k < 3; ++k)
        sizes[f] = std::max(sizes[f], (corners[f][static_cast<std::size_t>(k)] - corners[f][static_cast<std::size_t>((k + 1) % 3)]).norm());
    std::vector<double> sorted = sizes;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted.empty() ? 2.0 : sorted[sorted.size() / 2];
    cells_ = std::max(1, std::min(64, static_cast<int>(2.0 / std::max(median, 1e-6))));
    for (std::size_t f = 0; f < corners.size(); ++f) {
      Eigen::Vector3d lo = corners[f][0], hi = corners[f][0];
      for (const auto& v : corners[f]) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      const auto l = cell((lo.array() - sizes[f]).matrix()), h = cell((hi.array() + sizes[f]).matrix());
      for (int i = l[0]; i <= h[0]; ++i)
        for (int j = l[1]; j <= h[1]; ++j)
          for (int k = l[2]; k <= h[2]; ++k) buckets_[key({i, j, k})].push_back(static_cast<int>(f));
    }
  }
  const std::vector<int>& faces_near(const Eigen::Vector3d& q) const {
    static const std::vector<int> none;
    const auto it = buckets_.find(key(cell(q)));
    return it == buckets_.end() ? none : it->second;
  }

 private:
  std::array<int, 3> cell(const Eigen::Vector3d& p) const {
    std::array<int, 3> c{};
    for (int k = 0; k < 3; ++k)
      c[static_cast<std::size_t>(k)] = std::clamp(static_cast<int>((p(k) + 1) / 2 * cells_), 0, cells_ - 1);
    return c;
  }
  long key(const std::array<int, 3>& c) const { return (static_cast<long>(c[0]) * cells_ + c[1]) * cells_ + c[2]; }
  int cells_ = 1;
  std::unordered_map<long, std::vector<int>> buckets_;
};

std::array<double, 6> shape_functions(const Eigen::Vector3d& l) {
  return {l(0) * (2 * l(0) - 1), l(1) * (2 * l(1) - 1), l(2) * (2 * l(2) - 1), 4 * l(0) * l(1), 4 * l(1) * l(2), 4 * l(2) * l(0)};
}

// The flat-chord coordinates put the point O(h^2 curvature) off its place on the curved face:
// Gauss-Newton on min |x(l) - p|^2 moves it to the face's nearest point. (The ray from the centre
// through p, which the flat coordinates follow, grazes the broad faces of a thin body near its
// rim: intersecting it with the curved face there put the 0.069:0.175:0.982 entry's points up to
// 10^4 face sizes away, and their interpolated |u| 5e4 times the largest nodal one.)
Eigen::Vector3d refine_on_curved_face(std::span<const std::array<double, 3>> nodes_m, const std::array<std::int32_t, 6>& face,
                                      const Eigen::Vector3d& p, Eigen::Vector3d l) {
  std::array<Eigen::Vector3d, 6> x;
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& n = nodes_m[static_cast<std::size_t>(face[k])];
    x[k] = {n[0], n[1], n[2]};
  }
  for (int iteration = 0; iteration < 8; ++iteration) {
    const auto n = shape_functions(l);
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < 6; ++k) position += n[k] * x[k];
    // d/dl1 and d/dl2 with l0 = 1 - l1 - l2.
    const double l0 = l(0), l1 = l(1), l2 = l(2);
    const Eigen::Vector3d d1 = -(4 * l0 - 1) * x[0] + (4 * l1 - 1) * x[1] + 4 * (l0 - l1) * x[3] + 4 * l2 * x[4] - 4 * l2 * x[5];
    const Eigen::Vector3d d2 = -(4 * l0 - 1) * x[0] + (4 * l2 - 1) * x[2] - 4 * l1 * x[3] + 4 * l1 * x[4] + 4 * (l0 - l2) * x[5];
    Eigen::Matrix<double, 3, 2> j;
    j << d1, d2;
    Eigen::Vector2d step = (j.transpose() * j).ldlt().solve(j.transpose() * (p - position));
    if (!step.allFinite()) break;
    // A face is nearly flat: a step beyond half its size is the quadratic's far branch, not the point.
    if (step.norm() > 0.5) step *= 0.5 / step.norm();
    l(1) += step(0);
    l(2) += step(1);
    l(0) = 1 - l(1) - l(2);
    if (step.norm() < 1e-13) break;
  }
  return l;
}

}  // namespace

double surface_node_spacing_m(std::span<const std::array<double, 3>> nodes_m,
                              std::span<const std::array<std::int32_t, 6>> faces) {
  double sum = 0;
  for (const auto& f : faces)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& p = nodes_m[static_cast<std::size_t>(f[k])];
      const auto& q = nodes_m[static_cast<std::size_t>(f[(k + 1) % 3])];
      sum += std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
    }
  return faces.empty() ? 0.0 : sum / (3.0 * static_cast<double>(faces.size())) / 2;
}

struct SurfaceLocator::Impl {
  Eigen::Vector3d inverse_axes;
  std::span<const std::array<double, 3>> nodes_m;
  std::span<const std::array<std::int32_t, 6>> faces;
  std::vector<Eigen::Matrix3d> inverses;  // per face: unit-sphere corners -> barycentric
  std::optional<FaceGrid> grid;
  Eigen::Vector3d to_sphere(const Eigen::Vector3d& x) const { return x.cwiseProduct(inverse_axes).normalized(); }
};

SurfaceLocator::SurfaceLocator(const std::array<double, 3>& axes_m, std::span<const std::array<double, 3>> nodes_m,
                               std::span<const std::array<std::int32_t, 6>> faces)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.inverse_axes = {1 / axes_m[0], 1 / axes_m[1], 1 / axes_m[2]};
  m.nodes_m = nodes_m;
  m.faces = faces;
  std::vector<std::array<Eigen::Vector3d, 3>> corners(faces.size());
  m.inverses.resize(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    Eigen::Matrix3d c;
    for (int k = 0; k < 3; ++k) {
      const auto& n = nodes_m[static_cast<std::size_t>(faces[f][static_cast<std::size_t>(k)])];
      corners[f][static_cast<std::size_t>(k)] = m.to_sphere({n[0], n[1], n[2]});
      c.col(k) = corners[f][static_cast<std::size_t>(k)];
    }
    m.inverses[f] = c.inverse();
  }
  m.grid.emplace(corners);
}

SurfaceLocator::~SurfaceLocator() = default;
SurfaceLocator::SurfaceLocator(SurfaceLocator&&) noexcept = default;
SurfaceLocator& SurfaceLocator::operator=(SurfaceLocator&&) noexcept = default;

SurfacePoint SurfaceLocator::locate(const Eigen::Vector3d& x) const {
  const Impl& m = *impl_;
  const Eigen::Vector3d q = m.to_sphere(x);
  struct Candidate {
    double min_l;
    int face;
    Eigen::Vector3d l;
  };
  std::vector<Candidate> candidates;
  for (int f : m.grid->faces_near(q)) {
    Eigen::Vector3d l = m.inverses[static_cast<std::size_t>(f)] * q;
    if (l.sum() <= 0) continue;  // the ray meets the far side
    l /= l.sum();
    candidates.push_back({l.minCoeff(), f, l});
  }
  const auto order = [](const Candidate& p, const Candidate& r) {
    return p.min_l != r.min_l ? p.min_l > r.min_l : p.face < r.face;
  };
  // The ray's face first; the rest ordered only when it is needed (below).
  if (!candidates.empty()) std::iter_swap(candidates.begin(), std::min_element(candidates.begin(), candidates.end(), order));
  if (candidates.empty() || candidates.front().min_l < -1e-6)
    throw std::runtime_error("surface interpolation: a point of the ellipsoid lies on no face of its mesh (min "
                             "barycentric " + std::to_string(candidates.empty() ? -1e300 : candidates.front().min_l) + ")");
  // The face the ray crosses holds the nearest point, except where the ray grazes the surface
  // (a thin body near its rim): there the nearest point may lie on a neighbour, whose flat
  // coordinates are then nearly inside too. The face whose refined coordinates are most inside wins.
  constexpr double kInside = 1e-9, kNeighbour = -0.5;
  const auto refined = [&](const Candidate& c) {
    const Eigen::Vector3d start = c.l.cwiseMax(0.0) / c.l.cwiseMax(0.0).sum();
    return refine_on_curved_face(m.nodes_m, m.faces[static_cast<std::size_t>(c.face)], x, start);
  };
  int best = candidates.front().face;
  Eigen::Vector3d best_l = refined(candidates.front());
  if (!best_l.allFinite())  // no refinement converged: the flat coordinates of the ray's face
    best_l = candidates.front().l.cwiseMax(0.0) / candidates.front().l.cwiseMax(0.0).sum();
  if (best_l.minCoeff() < -kInside) {
    std::sort(candidates.begin() + 1, candidates.end(), order);
    for (std::size_t i = 1; i < candidates.size() && candidates[i].min_l >= kNeighbour; ++i) {
      const Eigen::Vector3d l = refined(candidates[i]);
      if (l.allFinite() && l.minCoeff() > best_l.minCoeff()) {
        best = candidates[i].face;
        best_l = l;
        if (l.minCoeff() >= -kInside) break;
      }
    }
  }
  return {m.faces[static_cast<std::size_t>(best)], shape_functions(best_l)};
}

Eigen::Vector3d SurfacePoint::vector(std::span<const double> nodal) const {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < 6; ++k) {
    const auto at = 3 * static_cast<std::size_t>(nodes[k]);
    out += weights[k] * Eigen::Vector3d(nodal[at], nodal[at + 1], nodal[at + 2]);
  }
  return out;
}

SurfaceInterpolator::SurfaceInterpolator(const std::array<double, 3>& axes_m, std::span<const std::array<double, 3>> nodes_m,
                                         std::span<const std::array<std::int32_t, 6>> faces,
                                         std::span<const Eigen::Vector3d> points) {
  const SurfaceLocator locator(axes_m, nodes_m, faces);
  for (const auto& x : points) points_.push_back(locator.locate(x));
}

std::vector<Eigen::Vector3d> SurfaceInterpolator::vectors(std::span<const double> nodal) const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points_.size());
  for (const auto& p : points_) out.push_back(p.vector(nodal));
  return out;
}

}  // namespace clatter::kernels::transfer
