#pragma once
// Closed triangle meshes made in the test instead of stored, wound counter-clockwise seen from
// outside: an icosphere (vertices on the sphere), a box whose faces are split into n x n squares, a
// bar with its own divisions per axis, a capped cylinder (caps fanned from the centre) and a thin
// disk with ringed faces; and an OBJ writer for tests that go through the scene reader.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/mesh.hpp"

namespace clatter::test {

// An icosahedron subdivided `levels` times, every vertex pushed onto the sphere of radius_m about
// `centre_m`: 20 * 4^levels triangles.
inline io::TriangleMesh icosphere(double radius_m, int levels, std::array<double, 3> centre_m = {0, 0, 0}) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> v{{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto unit = [](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] / n, p[1] / n, p[2] / n};
  };
  for (auto& p : v) p = unit(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      v.push_back(unit({v[a][0] + v[b][0], v[a][1] + v[b][1], v[a][2] + v[b][2]}));
      return middle[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f) {
      const int ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], ab, ca}, {tri[1], bc, ab}, {tri[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  io::TriangleMesh m;
  for (const auto& p : v)
    m.vertices_m.push_back({centre_m[0] + radius_m * p[0], centre_m[1] + radius_m * p[1], centre_m[2] + radius_m * p[2]});
  m.triangles = std::move(f);
  return m;
}

// The box [0, size_m[0]] x [0, size_m[1]] x [0, size_m[2]], each face n x n squares of two triangles.
inline io::TriangleMesh box(std::array<double, 3> size_m, int n = 1) {
  io::TriangleMesh m;
  std::map<std::array<int, 3>, int> index;  // lattice point (i, j, k) in 0..n -> vertex
  auto vertex = [&](std::array<int, 3> ijk) {
    const auto it = index.find(ijk);
    if (it != index.end()) return it->second;
    m.vertices_m.push_back({size_m[0] * ijk[0] / n, size_m[1] * ijk[1] / n, size_m[2] * ijk[2] / n});
    return index[ijk] = static_cast<int>(m.vertices_m.size()) - 1;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) right-handed
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto corner = [&](int di, int dj) {
            std::array<int, 3> ijk{};
            ijk[axis] = side * n, ijk[u] = i + di, ijk[w] = j + dj;
            return vertex(ijk);
          };
          const int a = corner(0, 0), b = corner(1, 0), c = corner(1, 1), d = corner(0, 1);
          // Seen from +axis, (u, w) turn counter-clockwise; the far side (+) keeps that order.
          if (side == 1) m.triangles.insert(m.triangles.end(), {{a, b, c}, {a, c, d}});
          else m.triangles.insert(m.triangles.end(), {{a, c, b}, {a, d, c}});
        }
    }
  return m;
}

// The closed cylinder of radius_m about the z axis from z = 0 to height_m: `segments` around,
// `rings` bands of two triangles a quad along it, each cap a fan about its centre.
inline io::TriangleMesh cylinder(double radius_m, double height_m, int segments, int rings) {
  io::TriangleMesh m;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const double a = 2 * 3.14159265358979323846 * i / segments;
      m.vertices_m.push_back({radius_m * std::cos(a), radius_m * std::sin(a), height_m * j / rings});
    }
  const int bottom = static_cast<int>(m.vertices_m.size());
  m.vertices_m.push_back({0, 0, 0});
  m.vertices_m.push_back({0, 0, height_m});
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const int a = j * segments + i, b = j * segments + (i + 1) % segments, c = b + segments, d = a + segments;
      m.triangles.insert(m.triangles.end(), {{a, b, c}, {a, c, d}});
    }
  for (int i = 0; i < segments; ++i) {
    const int next = (i + 1) % segments, top_ring = rings * segments;
    m.triangles.insert(m.triangles.end(), {{bottom, next, i}, {bottom + 1, top_ring + i, top_ring + next}});
  }
  return m;
}

// The box [0, size_m[0]] x [0, size_m[1]] x [0, size_m[2]] with cells[a] divisions along axis a,
// each face a grid of two-triangle rectangles: a slender bar keeps near-square faces (a bar
// 0.3 x 0.02 x 0.01 m with cells {60, 4, 2} has 5 mm squares) where box()'s n x n would stretch
// them.
inline io::TriangleMesh bar(std::array<double, 3> size_m, std::array<int, 3> cells) {
  io::TriangleMesh m;
  std::map<std::array<int, 3>, int> index;  // lattice point -> vertex
  auto vertex = [&](std::array<int, 3> ijk) {
    const auto it = index.find(ijk);
    if (it != index.end()) return it->second;
    m.vertices_m.push_back({size_m[0] * ijk[0] / cells[0], size_m[1] * ijk[1] / cells[1], size_m[2] * ijk[2] / cells[2]});
    return index[ijk] = static_cast<int>(m.vertices_m.size()) - 1;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) right-handed
      for (int i = 0; i < cells[u]; ++i)
        for (int j = 0; j < cells[w]; ++j) {
          auto corner = [&](int di, int dj) {
            std::array<int, 3> ijk{};
            ijk[axis] = side * cells[axis], ijk[u] = i + di, ijk[w] = j + dj;
            return vertex(ijk);
          };
          const int a = corner(0, 0), b = corner(1, 0), c = corner(1, 1), d = corner(0, 1);
          if (side == 1) m.triangles.insert(m.triangles.end(), {{a, b, c}, {a, c, d}});
          else m.triangles.insert(m.triangles.end(), {{a, c, b}, {a, d, c}});
        }
    }
  return m;
}

// A thin disk (a short capped cylinder) of radius_m about the z axis from z = 0 to thickness_m,
// `segments` around its rim and `rings` concentric bands on each face, so the faces' triangles are
// of the rim's size instead of cylinder()'s fans of slivers from the centre: ring j (of `rings`)
// at radius R j / rings holds max(6, segments j / rings) points (rounded to a multiple of 6, so
// neighbouring rings zip evenly), the rim `segments` (a multiple of 6). The rim's wall is one band
// (`wall_bands` more along z for a thick disk). Counter-clockwise seen from outside.
inline io::TriangleMesh disk(double radius_m, double thickness_m, int segments, int rings, int wall_bands = 1) {
  const double two_pi = 2 * 3.14159265358979323846;
  io::TriangleMesh m;
  std::vector<int> ring_size(static_cast<std::size_t>(rings) + 1);
  for (int j = 1; j <= rings; ++j) ring_size[j] = j == rings ? segments : std::max(6, 6 * ((segments * j / rings + 3) / 6));
  // One face's points: the centre, then each ring's points, counter-clockwise about +z.
  auto face = [&](double z) {
    std::vector<std::vector<int>> ids(static_cast<std::size_t>(rings) + 1);
    ids[0] = {static_cast<int>(m.vertices_m.size())};
    m.vertices_m.push_back({0, 0, z});
    for (int j = 1; j <= rings; ++j)
      for (int i = 0; i < ring_size[j]; ++i) {
        const double a = two_pi * i / ring_size[j], r = radius_m * j / rings;
        ids[j].push_back(static_cast<int>(m.vertices_m.size()));
        m.vertices_m.push_back({r * std::cos(a), r * std::sin(a), z});
      }
    return ids;
  };
  // Triangles between two rings, counter-clockwise about +z: the merge of their points by angle.
  auto band = [&](const std::vector<int>& inner, const std::vector<int>& outer, bool up) {
    const std::size_t ni = inner.size(), no = outer.size();
    std::size_t i = 0, o = 0;
    while (i < ni || o < no) {
      // Advance on the ring whose next point comes first in angle (inner: a fan when it is one point).
      const bool take_outer = ni == 1 || (o < no && (i == ni || (o + 1) * ni <= (i + 1) * no));
      std::array<int, 3> t = take_outer ? std::array<int, 3>{inner[i % ni], outer[o % no], outer[(o + 1) % no]}
                                        : std::array<int, 3>{inner[i % ni], outer[o % no], inner[(i + 1) % ni]};
      if (!up) std::swap(t[1], t[2]);
      m.triangles.push_back(t);
      (take_outer ? o : i) += 1;
      if (ni == 1 && o == no) break;
    }
  };
  std::vector<std::vector<int>> bottom = face(0), top = face(thickness_m), walls{bottom[rings]};
  for (int j = 0; j < rings; ++j) band(bottom[j], bottom[j + 1], false), band(top[j], top[j + 1], true);
  for (int k = 1; k < wall_bands; ++k) {
    walls.emplace_back();
    for (int i = 0; i < segments; ++i) {
      const double a = two_pi * i / segments;
      walls.back().push_back(static_cast<int>(m.vertices_m.size()));
      m.vertices_m.push_back({radius_m * std::cos(a), radius_m * std::sin(a), thickness_m * k / wall_bands});
    }
  }
  walls.push_back(top[rings]);
  for (std::size_t k = 0; k + 1 < walls.size(); ++k)
    for (int i = 0; i < segments; ++i) {
      const int a = walls[k][i], b = walls[k][(i + 1) % segments], c = walls[k + 1][(i + 1) % segments], d = walls[k + 1][i];
      m.triangles.insert(m.triangles.end(), {{a, b, c}, {a, c, d}});
    }
  return m;
}

// The mesh as the OBJ text clatter reads (io::obj_text: shortest round-trip numbers).
// False when the file cannot be written (a missing folder, a full disk): callers say so and fail.
inline bool write_obj(const io::TriangleMesh& m, const std::string& path) {
  std::ofstream out(path);
  out << io::obj_text(m);
  out.close();
  return static_cast<bool>(out);
}

}  // namespace clatter::test
