#include "kernels/pan/direction_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace clatter::kernels::pan {
namespace {

LatticePoint midpoint(const LatticePoint& p, const LatticePoint& q) { return {(p.a + q.a) / 2, (p.b + q.b) / 2}; }

// The children of an element with corners c and midpoints m (m[0] = M01, m[1] = M12, m[2] = M20),
// as corner triples (model::kChildCorners).
std::array<std::array<LatticePoint, 3>, 4> children_corners(const std::array<LatticePoint, 3>& c,
                                                            const std::array<LatticePoint, 3>& m) {
  const std::array<LatticePoint, 6> nodes{c[0], c[1], c[2], m[0], m[1], m[2]};
  std::array<std::array<LatticePoint, 3>, 4> out;
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t i = 0; i < 3; ++i) out[k][i] = nodes[static_cast<std::size_t>(model::kChildCorners[k][i])];
  return out;
}

// A child's barycentric coordinates from its parent's (children in the order above).
std::array<double, 3> child_coordinates(int child, const std::array<double, 3>& l) {
  switch (child) {
    case 0: return {2 * l[0] - 1, 2 * l[1], 2 * l[2]};
    case 1: return {2 * l[0], 2 * l[1] - 1, 2 * l[2]};
    case 2: return {2 * l[0], 2 * l[1], 2 * l[2] - 1};
    default: return {1 - 2 * l[0], 1 - 2 * l[1], 1 - 2 * l[2]};
  }
}

}  // namespace

DirectionMesh::DirectionMesh(int divisions, int max_levels)
    : divisions_(divisions), max_levels_(max_levels), lattice_(0) {
  if (divisions < 2 || divisions % 2 != 0 || max_levels < 0 || max_levels > 16 || divisions > (1 << 20) >> max_levels)
    throw std::invalid_argument("DirectionMesh: even divisions >= 2 and 0 to 16 levels on a lattice below 2^20");
  lattice_ = divisions << max_levels;
  const int s = 1 << max_levels, cells = divisions / 2, edge = 2 * s;
  for (int a = 0; a <= divisions; ++a)
    for (int b = 0; a + b <= divisions; ++b) vertex_at({a * s, b * s});
  // The roots in locate_direction's order: per cell, the upright element, then the inverted one.
  for (int a = 0; a < cells; ++a)
    for (int b = 0; a + b < cells; ++b) {
      std::vector<std::array<LatticePoint, 3>> corners{{{{a * edge, b * edge}, {(a + 1) * edge, b * edge}, {a * edge, (b + 1) * edge}}}};
      if (a + b + 1 < cells)
        corners.push_back({{{(a + 1) * edge, (b + 1) * edge}, {(a + 1) * edge, b * edge}, {a * edge, (b + 1) * edge}}});
      for (const auto& c : corners) {
        std::array<std::int32_t, 6> nodes{};
        for (int i = 0; i < 3; ++i) {
          nodes[static_cast<std::size_t>(i)] = vertex_at(c[static_cast<std::size_t>(i)]);
          nodes[static_cast<std::size_t>(3 + i)] = vertex_at(midpoint(c[static_cast<std::size_t>(i)], c[static_cast<std::size_t>((i + 1) % 3)]));
        }
        set_.elements.push_back(nodes);
        set_.first_child.push_back(-1);
        level_.push_back(0);
      }
    }
}

DirectionMesh::DirectionMesh(int divisions, int max_levels, const model::PanDirections& stored)
    : DirectionMesh(divisions, max_levels) {
  // Rebuild by replaying the splits the arrays record, then require the arrays to be exactly that
  // mesh: every check of the stored form in one comparison.
  const auto& first_child = stored.first_child;
  const std::size_t roots = set_.elements.size();
  if (stored.elements.size() < roots || first_child.size() != stored.elements.size())
    throw std::invalid_argument("DirectionMesh: fewer elements than the layout's roots, or a child list of another length");
  std::vector<std::pair<std::int32_t, std::size_t>> splits;  // (first child, parent), in the order they were made
  for (std::size_t e = 0; e < first_child.size(); ++e)
    if (first_child[e] >= 0) splits.push_back({first_child[e], e});
  std::sort(splits.begin(), splits.end());
  for (const auto& [c, e] : splits) {
    if (e >= set_.elements.size() || static_cast<std::size_t>(c) != set_.elements.size() || !can_split(e))
      throw std::invalid_argument("DirectionMesh: element " + std::to_string(e) + "'s children are not the next four elements");
    split(e);
  }
  if (stored.vertices != set_.vertices || stored.elements != set_.elements || first_child != set_.first_child)
    throw std::invalid_argument("DirectionMesh: the stored vertices and elements are not the splits they record");
}

std::array<double, 3> DirectionMesh::direction(const LatticePoint& p) const {
  const double x = p.a, y = p.b, z = lattice_ - p.a - p.b, n = std::sqrt(x * x + y * y + z * z);
  return {x / n, y / n, z / n};
}

int DirectionMesh::vertex_at(const LatticePoint& p) {
  const auto [it, added] = index_.try_emplace(lattice_key(p), static_cast<int>(set_.vertices.size()));
  if (added) set_.vertices.push_back(p);
  return it->second;
}

std::array<DirectionMesh::SplitPoint, 9> DirectionMesh::split_points(std::size_t element) const {
  const auto& n = set_.elements.at(element);
  auto at = [&](int i) { return set_.vertices[static_cast<std::size_t>(n[static_cast<std::size_t>(i)])]; };
  const std::array<LatticePoint, 3> c{at(0), at(1), at(2)}, m{at(3), at(4), at(5)};
  // The children's edge midpoints: six quarter points on the parent's edges, three inside.
  const std::array<std::pair<std::array<LatticePoint, 2>, std::array<double, 3>>, 9> points{{
      {{c[0], m[0]}, {0.75, 0.25, 0}}, {{m[0], c[1]}, {0.25, 0.75, 0}},
      {{c[1], m[1]}, {0, 0.75, 0.25}}, {{m[1], c[2]}, {0, 0.25, 0.75}},
      {{c[2], m[2]}, {0.25, 0, 0.75}}, {{m[2], c[0]}, {0.75, 0, 0.25}},
      {{m[0], m[2]}, {0.5, 0.25, 0.25}}, {{m[0], m[1]}, {0.25, 0.5, 0.25}}, {{m[1], m[2]}, {0.25, 0.25, 0.5}},
  }};
  std::array<SplitPoint, 9> out;
  for (std::size_t i = 0; i < 9; ++i) out[i] = {midpoint(points[i].first[0], points[i].first[1]), points[i].second};
  return out;
}

void DirectionMesh::split(std::size_t element) {
  if (!can_split(element)) throw std::invalid_argument("DirectionMesh: split of an element already split or at the deepest level");
  const auto n = set_.elements[element];
  auto at = [&](int i) { return set_.vertices[static_cast<std::size_t>(n[static_cast<std::size_t>(i)])]; };
  const std::array<LatticePoint, 3> c{at(0), at(1), at(2)}, m{at(3), at(4), at(5)};
  set_.first_child[element] = static_cast<std::int32_t>(set_.elements.size());
  const int level = level_[element] + 1;
  for (const auto& k : children_corners(c, m)) {
    std::array<std::int32_t, 6> nodes{};
    for (std::size_t i = 0; i < 3; ++i) {
      nodes[i] = vertex_at(k[i]);
      nodes[3 + i] = vertex_at(midpoint(k[i], k[(i + 1) % 3]));
    }
    set_.elements.push_back(nodes);
    set_.first_child.push_back(-1);
    level_.push_back(level);
  }
}

namespace {

// Quadratic weights of the six nodes n at barycentric coordinates l.
DirectionWeights quadratic_weights(const std::array<std::int32_t, 6>& n, const std::array<double, 3>& l) {
  DirectionWeights w;
  w.count = 6;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3;
    w.vertex[i] = n[i];
    w.weight[i] = l[i] * (2 * l[i] - 1);
    w.vertex[3 + i] = n[3 + i];
    w.weight[3 + i] = 4 * l[i] * l[j];
  }
  return w;
}

int child_holding(const std::array<double, 3>& l) { return l[0] >= 0.5 ? 0 : l[1] >= 0.5 ? 1 : l[2] >= 0.5 ? 2 : 3; }

}  // namespace

DirectionWeights DirectionMesh::weights(std::size_t element, const std::array<double, 3>& l) const {
  return quadratic_weights(set_.elements.at(element), l);
}

DirectionWeights DirectionMesh::locate(const std::array<double, 3>& d) const { return pan::locate(divisions_, set_, d); }

DirectionWeights locate(int divisions, const model::PanDirections& set, const std::array<double, 3>& d,
                        Interpolation interpolation) {
  const double s = d[0] + d[1] + d[2];
  if (!(s > 0) || d[0] < 0 || d[1] < 0 || d[2] < 0)
    throw std::invalid_argument("DirectionMesh::locate: direction outside the positive octant");
  // The root, as locate_direction finds its quadratic element.
  const int cells = divisions / 2;
  const double ua = cells * d[0] / s, ub = cells * d[1] / s;
  int a = std::min(static_cast<int>(std::floor(ua)), cells);
  int b = std::min(static_cast<int>(std::floor(ub)), cells - a);
  if (a + b == cells) {
    if (a > 0)
      --a;
    else
      --b;
  }
  const double fa = ua - a, fb = ub - b;
  const bool upright = fa + fb <= 1.0 || a + b + 1 == cells;
  std::array<double, 3> l = upright ? std::array<double, 3>{1.0 - fa - fb, fa, fb}
                                    : std::array<double, 3>{fa + fb - 1.0, 1.0 - fb, 1.0 - fa};
  for (double& x : l) x = std::clamp(x, 0.0, 1.0);
  // Roots are numbered row by row: row a holds 2 (cells - a) - 1 elements.
  std::size_t e = static_cast<std::size_t>(a * (2 * cells - a) + 2 * b + (upright ? 0 : 1));
  auto descend = [&] {
    const int child = child_holding(l);
    l = child_coordinates(child, l);
    for (double& x : l) x = std::clamp(x, 0.0, 1.0);
    return child;
  };
  while (set.first_child[e] >= 0) e = static_cast<std::size_t>(set.first_child[e] + descend());
  const auto& n = set.elements[e];
  if (interpolation == Interpolation::quadratic) return quadratic_weights(n, l);
  // Linear: the leaf's quarter holding d, the child a split would make there.
  const auto& q = model::kChildCorners[static_cast<std::size_t>(descend())];
  DirectionWeights w;
  w.count = 3;
  for (std::size_t i = 0; i < 3; ++i) {
    w.vertex[i] = n[static_cast<std::size_t>(q[i])];
    w.weight[i] = l[i];
  }
  return w;
}

DirectionMesh uniform_mesh(int divisions, int extra_levels) {
  int levels = 0;
  while ((2 << levels) < divisions) ++levels;
  if (divisions < 2 || (2 << levels) != divisions)
    throw std::invalid_argument("uniform_mesh: divisions must be 2 times a power of two, not " + std::to_string(divisions));
  DirectionMesh mesh(2, levels + extra_levels);
  for (std::size_t e = 0; e < mesh.elements().size(); ++e)  // children are appended: level by level
    if (mesh.level(e) < levels) mesh.split(e);
  return mesh;
}

int refine(DirectionMesh& mesh, const DirectionMiss& miss, double tolerance, std::size_t max_vertices,
           const DirectionsAhead& ahead) {
  int splits = 0;
  for (std::size_t e = 0; e < mesh.elements().size(); ++e) {  // children are appended: coarsest first
    if (!mesh.can_split(e) || mesh.size() + 9 > max_vertices) continue;
    const auto points = mesh.split_points(e);
    if (ahead) {
      std::vector<LatticePoint> at;
      for (const auto& p : points) at.push_back(p.point);
      ahead(at);
    }
    double worst = 0;
    for (const auto& p : points) worst = std::max(worst, miss(p.point, mesh.weights(e, p.l)));
    if (worst > tolerance) {
      mesh.split(e);
      ++splits;
    }
  }
  return splits;
}

}  // namespace clatter::kernels::pan
