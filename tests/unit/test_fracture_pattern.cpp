// 003 section 3.2's fracture pattern (kernels/fracture/pattern.*) on structured box meshes: the
// energy bound against a bar's cross-section (any crack separating its ends has area >= A), the
// pieces as a partition of the body into closed, outward, connected tetrahedral meshes, the
// fracture triangles pairing up and lying on the pieces' surfaces, the trends of strain energy and
// density, determinism, and the time on a 20k-tetrahedron mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <stdexcept>

#include "kernels/fracture/pattern.hpp"

namespace {
using namespace clatter;
using namespace clatter::kernels::fracture;

struct Box {
  TetMesh mesh;
  int nx, ny, nz;
  Vec3 size_m;
  int node(int i, int j, int k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
};

// nx*ny*nz hexahedra of h_m, each the 6 tetrahedra around its main diagonal (Kuhn), conforming
// across hexahedra; positively oriented.
Box box_mesh(int nx, int ny, int nz, const Vec3& h_m) {
  Box b{{}, nx, ny, nz, {nx * h_m[0], ny * h_m[1], nz * h_m[2]}};
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) b.mesh.nodes_m.push_back({i * h_m[0], j * h_m[1], k * h_m[2]});
  const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perm) {
          std::array<int, 3> c{i, j, k};
          std::array<int, 4> t{};
          t[0] = b.node(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = b.node(c[0], c[1], c[2]);
          }
          b.mesh.tets.push_back(t);
          if (tet_volume_m3(b.mesh, static_cast<int>(b.mesh.tets.size()) - 1) < 0)
            std::swap(b.mesh.tets.back()[2], b.mesh.tets.back()[3]);
        }
  return b;
}

Vec3 centroid(const TetMesh& m, int t) {
  Vec3 s{0, 0, 0};
  for (int v : m.tets[t]) s = add(s, m.nodes_m[v]);
  return scale(s, 0.25);
}

double mesh_volume(const TetMesh& m) {
  double v = 0;
  for (std::size_t t = 0; t < m.tets.size(); ++t) v += tet_volume_m3(m, static_cast<int>(t));
  return v;
}

double area(const std::array<Vec3, 3>& p) {
  const Vec3 n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
  return 0.5 * std::sqrt(dot(n, n));
}

// A triangle's points from its lowest point on, keeping the cyclic order (orientation).
std::array<Vec3, 3> canonical(std::array<Vec3, 3> p) {
  const int lo = static_cast<int>(std::min_element(p.begin(), p.end()) - p.begin());
  std::rotate(p.begin(), p.begin() + lo, p.end());
  return p;
}

// Everything that must hold for any pattern: the checks of the brief, each against geometry the
// test computes itself.
void check_pattern(const Box& box, const FracturePattern& pat, const PatternSettings& s, double strain_energy_j) {
  ASSERT_GE(pat.pieces.size(), 2u);
  EXPECT_EQ(pat.seeds, static_cast<int>(pat.pieces.size()));
  const double body_m3 = box.size_m[0] * box.size_m[1] * box.size_m[2];
  const double tol_m = 1e-12 * std::max({box.size_m[0], box.size_m[1], box.size_m[2]});

  // The fracture triangles: A_F, the bound, and each one's partner with the other orientation.
  double total_m2 = 0;
  std::map<std::array<Vec3, 3>, std::vector<int>> by_points;
  for (std::size_t i = 0; i < pat.fracture_triangles.size(); ++i) {
    const auto& f = pat.fracture_triangles[i];
    total_m2 += area(f.points_m);
    EXPECT_NE(f.piece, f.other);
    by_points[canonical(f.points_m)].push_back(static_cast<int>(i));
  }
  EXPECT_NEAR(pat.area_m2, total_m2 / 2, 1e-12 * total_m2);
  EXPECT_LE(s.fracture_energy_j_m2 * pat.area_m2, s.eta * strain_energy_j);
  EXPECT_DOUBLE_EQ(pat.fracture_energy_j, s.fracture_energy_j_m2 * pat.area_m2);
  for (const auto& [pts, ids] : by_points) {
    ASSERT_EQ(ids.size(), 1u) << "a fracture triangle repeated with the same orientation";
    const auto& f = pat.fracture_triangles[ids[0]];
    const auto twin = by_points.find(canonical({pts[0], pts[2], pts[1]}));
    ASSERT_NE(twin, by_points.end()) << "a fracture triangle without its other side";
    const auto& g = pat.fracture_triangles[twin->second[0]];
    EXPECT_EQ(f.piece, g.other);
    EXPECT_EQ(f.other, g.piece);
    EXPECT_EQ(f.tet, g.tet);
  }

  // The pieces: positive tetrahedra inside their source, volumes adding up to the body's.
  double pieces_m3 = 0;
  for (std::size_t p = 0; p < pat.pieces.size(); ++p) {
    const Piece& piece = pat.pieces[p];
    ASSERT_EQ(piece.source_tets.size(), piece.mesh.tets.size());
    ASSERT_FALSE(piece.mesh.tets.empty());
    double piece_m3 = 0;
    for (std::size_t t = 0; t < piece.mesh.tets.size(); ++t) {
      const double v = tet_volume_m3(piece.mesh, static_cast<int>(t));
      EXPECT_GT(v, 0) << "piece " << p << " tet " << t;
      piece_m3 += v;
      // Inside the source tetrahedron: its centroid's barycentric coordinates all >= 0.
      const TetMesh& m = box.mesh;
      const auto& src = m.tets[piece.source_tets[t]];
      const Vec3 c = centroid(piece.mesh, static_cast<int>(t));
      const double whole = tet_volume_m3(m, piece.source_tets[t]);
      for (int face = 0; face < 4; ++face) {
        std::array<Vec3, 4> x{m.nodes_m[src[0]], m.nodes_m[src[1]], m.nodes_m[src[2]], m.nodes_m[src[3]]};
        x[face] = c;
        const double part = dot(sub(x[1], x[0]), cross(sub(x[2], x[0]), sub(x[3], x[0]))) / 6;
        EXPECT_GE(part, -1e-12 * whole);
      }
    }
    pieces_m3 += piece_m3;

    // The surface: every directed edge met once each way (closed, consistently oriented), its
    // enclosed volume by the divergence theorem the tetrahedra's.
    std::map<std::pair<int, int>, int> directed;
    double enclosed_m3 = 0;
    std::set<std::array<Vec3, 3>> fracture_here;
    for (const auto& f : pat.fracture_triangles)
      if (f.piece == static_cast<int>(p)) fracture_here.insert(canonical(f.points_m));
    std::size_t on_fracture = 0;
    for (const auto& tri : piece.surface) {
      for (int e = 0; e < 3; ++e) ++directed[{tri[e], tri[(e + 1) % 3]}];
      const std::array<Vec3, 3> x{piece.mesh.nodes_m[tri[0]], piece.mesh.nodes_m[tri[1]], piece.mesh.nodes_m[tri[2]]};
      enclosed_m3 += dot(x[0], cross(x[1], x[2])) / 6;
      // Either a fracture triangle of this piece, same orientation, or on the body's boundary.
      if (fracture_here.count(canonical(x))) {
        ++on_fracture;
        continue;
      }
      bool on_box_face = false;
      for (int a = 0; a < 3; ++a)
        for (double plane : {0.0, box.size_m[a]})
          on_box_face = on_box_face || (std::abs(x[0][a] - plane) < tol_m && std::abs(x[1][a] - plane) < tol_m &&
                                        std::abs(x[2][a] - plane) < tol_m);
      EXPECT_TRUE(on_box_face) << "piece " << p << ": a surface triangle neither fracture nor body boundary";
    }
    EXPECT_EQ(on_fracture, fracture_here.size()) << "piece " << p << ": fracture triangles missing from its surface";
    for (const auto& [e, n] : directed) {
      const auto back = directed.find({e.second, e.first});
      ASSERT_NE(back, directed.end()) << "piece " << p << ": open surface";
      EXPECT_EQ(n, back->second);
    }
    EXPECT_NEAR(enclosed_m3, piece_m3, 1e-10 * body_m3) << "piece " << p;

    // Face-connected: one flood over shared faces reaches every tetrahedron.
    std::map<std::array<int, 3>, std::vector<int>> faces;
    for (std::size_t t = 0; t < piece.mesh.tets.size(); ++t)
      for (int skip = 0; skip < 4; ++skip) {
        std::array<int, 3> key{};
        int n = 0;
        for (int v = 0; v < 4; ++v)
          if (v != skip) key[n++] = piece.mesh.tets[t][v];
        std::sort(key.begin(), key.end());
        faces[key].push_back(static_cast<int>(t));
      }
    std::vector<std::vector<int>> adj(piece.mesh.tets.size());
    for (const auto& [key, ts] : faces) {
      EXPECT_LE(ts.size(), 2u) << "piece " << p << ": a face shared by 3+ tetrahedra";
      if (ts.size() == 2) {
        adj[ts[0]].push_back(ts[1]);
        adj[ts[1]].push_back(ts[0]);
      }
    }
    std::vector<char> seen(piece.mesh.tets.size(), 0);
    std::vector<int> stack{0};
    seen[0] = 1;
    std::size_t reached = 1;
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int u : adj[t])
        if (!seen[u]) {
          seen[u] = 1;
          ++reached;
          stack.push_back(u);
        }
    }
    EXPECT_EQ(reached, piece.mesh.tets.size()) << "piece " << p << " is not face-connected";
  }
  EXPECT_NEAR(pieces_m3, body_m3, 1e-12 * body_m3);
}

std::vector<double> uniform_density(const Box& b, double w) { return std::vector<double>(b.mesh.tets.size(), w); }

// Energy density falling off from the x = 0 end (a load there).
std::vector<double> peaked_density(const Box& b) {
  std::vector<double> d;
  for (std::size_t t = 0; t < b.mesh.tets.size(); ++t)
    d.push_back(1e3 * std::exp(-centroid(b.mesh, static_cast<int>(t))[0] / (0.2 * b.size_m[0])));
  return d;
}

// The bar 7 x 2 x 2 hexahedra, 0.7 m long, 0.04 m x 0.04 m across; seeds at the centres of its
// end faces. Hexahedra 5x longer than wide: every node of the near half is closer (along edges)
// to the near seed, so the two regions are the node layers x <= 0.3 and x >= 0.4.
struct Bar {
  Box box = box_mesh(7, 2, 2, {0.1, 0.02, 0.02});
  double cross_section_m2 = 0.04 * 0.04;
  std::vector<int> end_seeds{box.node(0, 1, 1), box.node(7, 1, 1)};
};

// The dual-cell interface of the two halves, from the definition: over every edge between a node
// with x <= 0.3 and one with x >= 0.4, the quad (edge midpoint, the two face centroids, the
// tetrahedron's centroid) of each tetrahedron around it.
double bar_half_interface_m2(const Bar& bar) {
  const TetMesh& m = bar.box.mesh;
  double a = 0;
  for (const auto& t : m.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const bool left_i = m.nodes_m[t[i]][0] < 0.35, left_j = m.nodes_m[t[j]][0] < 0.35;
        if (left_i == left_j) continue;
        Vec3 c{0, 0, 0};
        for (int v : t) c = add(c, scale(m.nodes_m[v], 0.25));
        const Vec3 mid = scale(add(m.nodes_m[t[i]], m.nodes_m[t[j]]), 0.5);
        std::vector<Vec3> fc;
        for (int k = 0; k < 4; ++k)
          if (k != i && k != j) {
            Vec3 s{0, 0, 0};
            for (int v = 0; v < 4; ++v)
              if (v != k) s = add(s, scale(m.nodes_m[t[v]], 1.0 / 3));
            fc.push_back(s);
          }
        a += area({mid, fc[0], c}) + area({mid, c, fc[1]});
      }
  return a;
}

TEST(FracturePattern, CrackAcrossBarCostsItsCrossSection) {
  const Bar bar;
  const double a_ref = bar_half_interface_m2(bar);
  // The interface separates the end faces, so it covers the cross-section: A_F >= A (its zigzag
  // through the elongated tetrahedra makes it several times larger).
  EXPECT_GT(a_ref, bar.cross_section_m2);
  std::printf("bar: A = %.6g m2, dual-cell crack A_F = %.6g m2 (%.4f A)\n", bar.cross_section_m2, a_ref,
              a_ref / bar.cross_section_m2);

  PatternSettings s;
  s.fracture_energy_j_m2 = 250;
  s.seed_nodes = bar.end_seeds;
  const auto density = uniform_density(bar.box, 1e3);
  const double body_m3 = 0.7 * 0.04 * 0.04;
  // Below G_c A no crack across the bar can be paid for.
  EXPECT_TRUE(fracture_pattern(bar.box.mesh, density, 0.999 * s.fracture_energy_j_m2 * bar.cross_section_m2 / s.eta, s)
                  .pieces.empty());
  // Just below and just above this crack's own price.
  EXPECT_TRUE(fracture_pattern(bar.box.mesh, density, (1 - 1e-9) * s.fracture_energy_j_m2 * a_ref / s.eta, s)
                  .pieces.empty());
  const double e_s = (1 + 1e-9) * s.fracture_energy_j_m2 * a_ref / s.eta;
  const FracturePattern two = fracture_pattern(bar.box.mesh, density, e_s, s);
  ASSERT_EQ(two.pieces.size(), 2u);
  EXPECT_NEAR(two.area_m2, a_ref, 1e-12 * a_ref);
  check_pattern(bar.box, two, s, e_s);
  // The halves by symmetry of the cut through the middle hexahedron layer: the cut stays in it.
  const double left_m3 = mesh_volume(two.pieces[0].mesh);
  EXPECT_GT(left_m3, 3.0 / 7 * body_m3);
  EXPECT_LT(left_m3, 4.0 / 7 * body_m3);
  // Every whole tetrahedron of a piece is on its seed's side.
  for (int p = 0; p < 2; ++p)
    for (std::size_t t = 0; t < two.pieces[p].mesh.tets.size(); ++t) {
      const double x = centroid(bar.box.mesh, two.pieces[p].source_tets[t])[0];
      EXPECT_TRUE(p == 0 ? x < 0.4 : x > 0.3);
    }
}

TEST(FracturePattern, DenserSeedTakesSmallerRegion) {
  // k_i = density^alpha: with the x < 0.35 half 10^4 times denser, its seed's distances count
  // 10^(4 alpha) ~ 3.98 times more, and the cut moves from the middle to x ~ 0.7/4.98 = 0.14.
  const Bar bar;
  std::vector<double> density;
  for (std::size_t t = 0; t < bar.box.mesh.tets.size(); ++t)
    density.push_back(centroid(bar.box.mesh, static_cast<int>(t))[0] < 0.35 ? 1e4 : 1.0);
  PatternSettings s;
  s.fracture_energy_j_m2 = 1;
  s.seed_nodes = bar.end_seeds;
  const double body_m3 = 0.7 * 0.04 * 0.04, e_s = 1e3;
  const FracturePattern weighted = fracture_pattern(bar.box.mesh, density, e_s, s);
  ASSERT_EQ(weighted.pieces.size(), 2u);
  check_pattern(bar.box, weighted, s, e_s);
  const double dense_share = mesh_volume(weighted.pieces[0].mesh) / body_m3;
  EXPECT_GT(dense_share, 0.1);
  EXPECT_LT(dense_share, 0.3);
  s.alpha = 0;
  const FracturePattern even = fracture_pattern(bar.box.mesh, density, e_s, s);
  ASSERT_EQ(even.pieces.size(), 2u);
  const double even_share = mesh_volume(even.pieces[0].mesh) / body_m3;
  std::printf("dense seed's share of the bar: %.3f (alpha 0.15), %.3f (alpha 0)\n", dense_share, even_share);
  EXPECT_GT(even_share, 3.0 / 7);
  EXPECT_LT(even_share, 4.0 / 7);
}

TEST(FracturePattern, PiecesPartitionTheBody) {
  const Box box = box_mesh(8, 5, 4, {0.02, 0.02, 0.02});
  PatternSettings s;
  s.fracture_energy_j_m2 = 100;
  for (const bool peaked : {false, true})
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      s.seed = seed;
      const auto density = peaked ? peaked_density(box) : uniform_density(box, 1e3);
      const double e_s = 10;  // A_F <= 0.08 m2: a few zigzag cracks of 0.1 m x 0.08 m
      const FracturePattern pat = fracture_pattern(box.mesh, density, e_s, s);
      SCOPED_TRACE(::testing::Message() << "peaked " << peaked << " seed " << seed);
      std::printf("box 8x5x4, %s density, seed %d: %zu pieces, A_F %.4g m2\n", peaked ? "peaked" : "uniform",
                  static_cast<int>(seed), pat.pieces.size(), pat.area_m2);
      check_pattern(box, pat, s, e_s);
    }
  // Many pieces: each a few nodes' cells.
  s.seed = 7;
  s.max_pieces = 40;
  const double e_s = 1e3;
  const FracturePattern many = fracture_pattern(box.mesh, uniform_density(box, 1e3), e_s, s);
  EXPECT_EQ(many.pieces.size(), 40u);
  check_pattern(box, many, s, e_s);
}

TEST(FracturePattern, MoreStrainEnergyMorePieces) {
  const Box box = box_mesh(10, 4, 4, {0.02, 0.02, 0.02});
  const auto density = peaked_density(box);
  PatternSettings s;
  s.fracture_energy_j_m2 = 100;
  s.max_pieces = 60;
  const double crack_j = s.fracture_energy_j_m2 * 0.08 * 0.08 / s.eta;  // one crack across
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    s.seed = seed;
    std::size_t before = 0;
    for (double cracks : {0.5, 1.5, 3.0, 6.0, 12.0, 24.0, 1e6}) {
      const FracturePattern pat = fracture_pattern(box.mesh, density, cracks * crack_j, s);
      EXPECT_GE(pat.pieces.size(), before) << "seed " << seed << ", " << cracks << " cracks' energy";
      if (!pat.pieces.empty()) {
        EXPECT_LE(pat.fracture_energy_j, s.eta * cracks * crack_j);
      }
      before = pat.pieces.size();
      std::printf("%zu ", before);
    }
    std::printf("pieces (seed %d) for 0.5 .. 24 cracks' energy, unbounded\n", static_cast<int>(seed));
    EXPECT_EQ(before, 60u);  // unbounded energy: max_pieces decides
  }
  // A thousandth of a crack (a few percent of one element face) cuts nothing off, not even one node.
  EXPECT_TRUE(fracture_pattern(box.mesh, density, 1e-3 * crack_j, s).pieces.empty());
}

TEST(FracturePattern, DenseEndBreaksFiner) {
  // Seeds drawn by energy and k_i from the density: the pieces of the dense x < L/2 half are
  // smaller on average than those of the other half, over a few seeds.
  const Box box = box_mesh(12, 4, 4, {0.02, 0.02, 0.02});
  std::vector<double> density;
  for (std::size_t t = 0; t < box.mesh.tets.size(); ++t)
    density.push_back(centroid(box.mesh, static_cast<int>(t))[0] < 0.12 ? 100.0 : 1.0);
  PatternSettings s;
  s.fracture_energy_j_m2 = 1;
  s.max_pieces = 16;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    s.seed = seed;
    const FracturePattern pat = fracture_pattern(box.mesh, density, 1e6, s);
    ASSERT_EQ(pat.pieces.size(), 16u);
    double dense_m3 = 0, sparse_m3 = 0;
    int dense_n = 0, sparse_n = 0;
    for (const auto& piece : pat.pieces) {
      double v = 0, x = 0;
      for (std::size_t t = 0; t < piece.mesh.tets.size(); ++t) {
        const double vt = tet_volume_m3(piece.mesh, static_cast<int>(t));
        v += vt;
        x += vt * centroid(piece.mesh, static_cast<int>(t))[0];
      }
      (x / v < 0.12 ? dense_m3 : sparse_m3) += v;
      ++(x / v < 0.12 ? dense_n : sparse_n);
    }
    std::printf("seed %d: %d dense pieces of mean %.3g m3, %d sparse of %.3g m3\n", static_cast<int>(seed), dense_n,
                dense_m3 / std::max(dense_n, 1), sparse_n, sparse_m3 / std::max(sparse_n, 1));
    ASSERT_GT(dense_n, 0);
    ASSERT_GT(sparse_n, 0);
    EXPECT_LT(dense_m3 / dense_n, sparse_m3 / sparse_n) << "seed " << seed << ": " << dense_n << " dense pieces, "
                                                        << sparse_n << " sparse";
  }
}

bool same(const FracturePattern& a, const FracturePattern& b) {
  if (a.pieces.size() != b.pieces.size() || a.fracture_triangles.size() != b.fracture_triangles.size()) return false;
  for (std::size_t p = 0; p < a.pieces.size(); ++p) {
    const Piece &x = a.pieces[p], &y = b.pieces[p];
    if (x.mesh.nodes_m != y.mesh.nodes_m || x.mesh.tets != y.mesh.tets || x.source_tets != y.source_tets ||
        x.surface != y.surface)
      return false;
  }
  for (std::size_t i = 0; i < a.fracture_triangles.size(); ++i) {
    const auto &f = a.fracture_triangles[i], &g = b.fracture_triangles[i];
    if (f.points_m != g.points_m || f.piece != g.piece || f.other != g.other || f.tet != g.tet) return false;
  }
  return a.area_m2 == b.area_m2 && a.fracture_energy_j == b.fracture_energy_j && a.seeds == b.seeds;
}

TEST(FracturePattern, Deterministic) {
  const Box box = box_mesh(8, 5, 4, {0.02, 0.02, 0.02});
  const auto density = peaked_density(box);
  PatternSettings s;
  s.fracture_energy_j_m2 = 100;
  const FracturePattern a = fracture_pattern(box.mesh, density, 10, s);
  const FracturePattern b = fracture_pattern(box.mesh, density, 10, s);
  ASSERT_GE(a.pieces.size(), 2u);
  EXPECT_TRUE(same(a, b));
  s.seed = 2;  // and the seed matters
  EXPECT_FALSE(same(a, fracture_pattern(box.mesh, density, 10, s)));
}

TEST(FracturePattern, RefusesBadInput) {
  const Box box = box_mesh(2, 1, 1, {0.1, 0.1, 0.1});
  PatternSettings s;
  s.fracture_energy_j_m2 = 1;
  EXPECT_THROW(fracture_pattern(box.mesh, std::vector<double>(3, 1.0), 1, s), std::invalid_argument);
  auto negative = uniform_density(box, 1);
  negative[0] = -1;
  EXPECT_THROW(fracture_pattern(box.mesh, negative, 1, s), std::invalid_argument);
  PatternSettings no_gc;
  EXPECT_THROW(fracture_pattern(box.mesh, uniform_density(box, 1), 1, no_gc), std::invalid_argument);
  PatternSettings twice = s;
  twice.seed_nodes = {0, 0};
  EXPECT_THROW(fracture_pattern(box.mesh, uniform_density(box, 1), 1, twice), std::invalid_argument);
  // Two boxes side by side, sharing nothing.
  TetMesh two = box.mesh;
  const int offset = static_cast<int>(two.nodes_m.size());
  for (const auto& x : box.mesh.nodes_m) two.nodes_m.push_back(add(x, {1, 0, 0}));
  for (auto t : box.mesh.tets) {
    for (int& v : t) v += offset;
    two.tets.push_back(t);
  }
  EXPECT_THROW(fracture_pattern(two, std::vector<double>(two.tets.size(), 1.0), 1, s), std::invalid_argument);
}

TEST(FracturePattern, TwentyThousandTetsTiming) {
  const Box box = box_mesh(20, 14, 12, {0.01, 0.01, 0.01});  // 20160 tetrahedra
  ASSERT_EQ(box.mesh.tets.size(), 20160u);
  const auto density = peaked_density(box);
  PatternSettings s;
  s.fracture_energy_j_m2 = 100;
  s.max_pieces = 60;
  const auto start = std::chrono::steady_clock::now();
  const FracturePattern pat = fracture_pattern(box.mesh, density, 1e6, s);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(pat.pieces.size(), 60u);
  std::size_t piece_tets = 0;
  for (const auto& p : pat.pieces) piece_tets += p.mesh.tets.size();
  std::printf("20160 tets -> %zu pieces, %zu piece tets, %zu fracture triangles, A_F %.4g m2: %.3f s\n",
              pat.pieces.size(), piece_tets, pat.fracture_triangles.size(), pat.area_m2, wall_s);
  EXPECT_LT(wall_s, 5.0);
  check_pattern(box, pat, s, 1e6);
}

}  // namespace
