#include "kernels/fracture/pattern.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace clatter::kernels::fracture {

namespace {

// Local edges, and local faces opposite vertex 0..3 counter-clockwise seen from outside a positive
// tetrahedron (as boundary_faces).
constexpr int kEdge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// The two local vertices not on local edge e: the faces opposite them are the two containing e.
std::array<int, 2> off_edge(int e) {
  std::array<int, 2> out{};
  int n = 0;
  for (int v = 0; v < 4; ++v)
    if (v != kEdge[e][0] && v != kEdge[e][1]) out[n++] = v;
  return out;
}

double triangle_area_m2(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(sub(b, a), sub(c, a));
  return 0.5 * std::sqrt(dot(n, n));
}

double signed_volume_m3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(sub(b, a), cross(sub(c, a), sub(d, a))) / 6;
}

// Midpoints and centroids from node ids in ascending order, so that every tetrahedron sharing an
// edge or a face computes the same bits.
Vec3 mean_of(const TetMesh& mesh, std::array<int, 3> ids, int count) {
  std::sort(ids.begin(), ids.begin() + count);
  Vec3 s{0, 0, 0};
  for (int i = 0; i < count; ++i) s = add(s, mesh.nodes_m[ids[i]]);
  return scale(s, 1.0 / count);
}

Vec3 tet_centroid(const TetMesh& mesh, const std::array<int, 4>& t) {
  Vec3 s{0, 0, 0};
  for (int v : t) s = add(s, mesh.nodes_m[v]);
  return scale(s, 0.25);
}

// The mesh's undirected edges (ascending pairs, sorted), their lengths, the node adjacency over them
// (CSR) and each tetrahedron's 6 edge ids.
struct EdgeGraph {
  std::vector<std::pair<int, int>> edges;
  std::vector<double> length_m;
  std::vector<int> offset, neighbour, neighbour_edge;
  std::vector<std::array<int, 6>> tet_edges;
};

EdgeGraph edge_graph(const TetMesh& mesh) {
  EdgeGraph g;
  const int n = static_cast<int>(mesh.nodes_m.size());
  g.edges.reserve(mesh.tets.size() * 6);
  for (const auto& t : mesh.tets)
    for (const auto& e : kEdge) g.edges.emplace_back(std::min(t[e[0]], t[e[1]]), std::max(t[e[0]], t[e[1]]));
  std::sort(g.edges.begin(), g.edges.end());
  g.edges.erase(std::unique(g.edges.begin(), g.edges.end()), g.edges.end());
  const int m = static_cast<int>(g.edges.size());
  g.length_m.resize(m);
  g.offset.assign(n + 1, 0);
  for (int i = 0; i < m; ++i) {
    const auto [a, b] = g.edges[i];
    const Vec3 d = sub(mesh.nodes_m[b], mesh.nodes_m[a]);
    g.length_m[i] = std::sqrt(dot(d, d));
    ++g.offset[a + 1];
    ++g.offset[b + 1];
  }
  for (int i = 0; i < n; ++i) g.offset[i + 1] += g.offset[i];
  g.neighbour.resize(2 * m);
  g.neighbour_edge.resize(2 * m);
  std::vector<int> fill(g.offset.begin(), g.offset.end() - 1);
  for (int i = 0; i < m; ++i) {
    const auto [a, b] = g.edges[i];
    g.neighbour[fill[a]] = b;
    g.neighbour_edge[fill[a]++] = i;
    g.neighbour[fill[b]] = a;
    g.neighbour_edge[fill[b]++] = i;
  }
  g.tet_edges.resize(mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    for (int e = 0; e < 6; ++e) {
      const int a = mesh.tets[t][kEdge[e][0]], b = mesh.tets[t][kEdge[e][1]];
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      g.tet_edges[t][e] = static_cast<int>(std::lower_bound(g.edges.begin(), g.edges.end(), key) - g.edges.begin());
    }
  return g;
}

// The interface quad (m_ij, c_f1, c_T, c_f2) of local edge e as its two triangles, split along
// m_ij-c_T as the dual-cell sub-tetrahedra meet there.
std::array<std::array<Vec3, 3>, 2> interface_quad(const TetMesh& mesh, const std::array<int, 4>& t, int e) {
  const auto [k1, k2] = off_edge(e);
  const auto face_centroid = [&](int opposite) {
    return mean_of(mesh, {t[kFace[opposite][0]], t[kFace[opposite][1]], t[kFace[opposite][2]]}, 3);
  };
  const Vec3 m = mean_of(mesh, {t[kEdge[e][0]], t[kEdge[e][1]], 0}, 2);
  const Vec3 c = tet_centroid(mesh, t);
  const Vec3 f1 = face_centroid(k1), f2 = face_centroid(k2);
  return {{{m, f1, c}, {m, c, f2}}};
}

// splitmix64: a fixed, portable stream for the seed sampling.
std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Weighted sampling without replacement (Efraimidis-Spirakis): node n's key log(u_n)/w_n, the
// largest keys first, draws the same distribution as repeated proportional draws from the nodes
// left, in one sort.
std::vector<int> sample_seeds(const std::vector<double>& weight, std::uint64_t seed, int count) {
  std::uint64_t state = seed;
  std::vector<std::pair<double, int>> key;
  for (std::size_t n = 0; n < weight.size(); ++n) {
    const double u = (static_cast<double>(splitmix64(state) >> 11) + 1) * 0x1.0p-53;  // (0, 1]
    if (weight[n] > 0) key.emplace_back(std::log(u) / weight[n], static_cast<int>(n));
  }
  const auto first = [](const std::pair<double, int>& a, const std::pair<double, int>& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  };
  const std::size_t k = std::min<std::size_t>(key.size(), static_cast<std::size_t>(std::max(count, 0)));
  std::partial_sort(key.begin(), key.begin() + static_cast<std::ptrdiff_t>(k), key.end(), first);
  std::vector<int> out(k);
  for (std::size_t i = 0; i < k; ++i) out[i] = key[i].second;
  return out;
}

// Region growing from all seeds at once: a node is captured by the region whose weighted path
// length k_i * (edges from p_i through that region) reaches it first; ties to the lower region.
class RegionGrower {
 public:
  explicit RegionGrower(const EdgeGraph& graph, int nodes) : g_(graph), value_(nodes), settled_(nodes) {}

  void grow(const std::vector<int>& seed_nodes, const std::vector<double>& k, std::vector<int>& region) {
    using Entry = std::tuple<double, int, int>;  // value, region, node
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    std::fill(value_.begin(), value_.end(), std::numeric_limits<double>::infinity());
    std::fill(settled_.begin(), settled_.end(), 0);
    region.assign(value_.size(), -1);
    for (std::size_t i = 0; i < seed_nodes.size(); ++i) {
      value_[seed_nodes[i]] = 0;
      region[seed_nodes[i]] = static_cast<int>(i);
      queue.emplace(0.0, static_cast<int>(i), seed_nodes[i]);
    }
    while (!queue.empty()) {
      const auto [d, r, x] = queue.top();
      queue.pop();
      if (settled_[x]) continue;
      settled_[x] = 1;
      for (int p = g_.offset[x]; p < g_.offset[x + 1]; ++p) {
        const int y = g_.neighbour[p];
        if (settled_[y]) continue;
        const double dy = d + k[r] * g_.length_m[g_.neighbour_edge[p]];
        if (dy < value_[y] || (dy == value_[y] && r < region[y])) {
          value_[y] = dy;
          region[y] = r;
          queue.emplace(dy, r, y);
        }
      }
    }
  }

 private:
  const EdgeGraph& g_;
  std::vector<double> value_;
  std::vector<char> settled_;
};

void check_input(const TetMesh& mesh, const std::vector<double>& density, double strain_energy_j,
                 const PatternSettings& s) {
  const auto fail = [](const std::string& why) { throw std::invalid_argument("fracture_pattern: " + why); };
  if (density.size() != mesh.tets.size()) fail("one energy density per tetrahedron expected");
  for (double d : density)
    if (!(d >= 0) || !std::isfinite(d)) fail("energy densities must be finite and >= 0");
  if (!(s.fracture_energy_j_m2 > 0) || !std::isfinite(s.fracture_energy_j_m2)) fail("G_c must be > 0");
  if (!(s.eta > 0 && s.eta <= 1)) fail("eta must lie in (0, 1]");
  if (!(s.alpha >= 0) || !std::isfinite(s.alpha)) fail("alpha must be >= 0");
  if (!(strain_energy_j >= 0) || !std::isfinite(strain_energy_j)) fail("strain energy must be finite and >= 0");
  const int n = static_cast<int>(mesh.nodes_m.size());
  for (const auto& t : mesh.tets)
    for (int v : t)
      if (v < 0 || v >= n) fail("tetrahedron node index out of range");
  std::vector<char> used(n, 0);
  for (const auto& t : mesh.tets)
    for (int v : t) used[v] = 1;
  std::vector<char> seen(n, 0);
  for (int v : s.seed_nodes) {
    if (v < 0 || v >= n || !used[v]) fail("seed node " + std::to_string(v) + " is not a node of a tetrahedron");
    if (seen[v]) fail("seed node " + std::to_string(v) + " given twice");
    seen[v] = 1;
  }
}

// Every node of a tetrahedron reachable from the first one: the regions must cover the body.
void check_connected(const TetMesh& mesh, const EdgeGraph& g) {
  const int n = static_cast<int>(mesh.nodes_m.size());
  if (mesh.tets.empty()) return;
  std::vector<char> seen(n, 0);
  std::vector<int> stack{mesh.tets[0][0]};
  seen[stack[0]] = 1;
  while (!stack.empty()) {
    const int x = stack.back();
    stack.pop_back();
    for (int p = g.offset[x]; p < g.offset[x + 1]; ++p)
      if (!seen[g.neighbour[p]]) {
        seen[g.neighbour[p]] = 1;
        stack.push_back(g.neighbour[p]);
      }
  }
  for (const auto& t : mesh.tets)
    for (int v : t)
      if (!seen[v]) throw std::invalid_argument("fracture_pattern: the mesh is not connected");
}

// The pieces, their surfaces and the fracture triangles of a final node labelling.
FracturePattern build_pattern(const TetMesh& mesh, const EdgeGraph& g, const std::vector<int>& region,
                              int regions, const std::vector<double>& quad_area_m2) {
  const int tets = static_cast<int>(mesh.tets.size());
  const auto split_tet = [&](int t) {
    const auto& n = mesh.tets[t];
    return region[n[0]] != region[n[1]] || region[n[0]] != region[n[2]] || region[n[0]] != region[n[3]];
  };
  // Every edge of a split tetrahedron carries a midpoint; every tetrahedron with such an edge is
  // subdivided with it, whole or not, so that neighbours stay conforming.
  std::vector<char> edge_cut(g.edges.size(), 0);
  for (int t = 0; t < tets; ++t)
    if (split_tet(t))
      for (int e : g.tet_edges[t]) edge_cut[e] = 1;

  std::vector<Vec3> points = mesh.nodes_m;
  std::vector<int> midpoint(g.edges.size(), -1);
  std::map<std::array<int, 3>, int> face_point;
  const auto mid_id = [&](int e) {
    if (midpoint[e] < 0) {
      midpoint[e] = static_cast<int>(points.size());
      points.push_back(mean_of(mesh, {g.edges[e].first, g.edges[e].second, 0}, 2));
    }
    return midpoint[e];
  };
  const auto face_id = [&](std::array<int, 3> f) {
    std::sort(f.begin(), f.end());
    const auto [it, fresh] = face_point.try_emplace(f, static_cast<int>(points.size()));
    if (fresh) points.push_back(mean_of(mesh, f, 3));
    return it->second;
  };

  std::vector<std::vector<std::array<int, 4>>> piece_tets(regions);
  std::vector<std::vector<int>> piece_source(regions);
  FracturePattern out;
  for (int t = 0; t < tets; ++t) {
    const auto& n = mesh.tets[t];
    const auto& te = g.tet_edges[t];
    bool refined = false;
    for (int e : te) refined = refined || edge_cut[e];
    if (!refined) {
      piece_tets[region[n[0]]].push_back(n);
      piece_source[region[n[0]]].push_back(t);
      continue;
    }
    const int centre = static_cast<int>(points.size());
    points.push_back(tet_centroid(mesh, n));
    const auto local_edge = [&](int a, int b) {
      for (int e = 0; e < 6; ++e)
        if ((kEdge[e][0] == a && kEdge[e][1] == b) || (kEdge[e][0] == b && kEdge[e][1] == a)) return e;
      return -1;
    };
    std::array<int, 4> face_centre{-1, -1, -1, -1};
    for (int f = 0; f < 4; ++f) {
      // The face's boundary, corners and the midpoints of its cut edges, counter-clockwise from
      // outside; fanned from the face centroid where any edge is cut.
      std::array<std::pair<int, int>, 6> poly{};  // point, local corner (-1: a midpoint)
      int size = 0;
      for (int s = 0; s < 3; ++s) {
        const int a = kFace[f][s], b = kFace[f][(s + 1) % 3];
        poly[size++] = {n[a], a};
        const int e = te[local_edge(a, b)];
        if (edge_cut[e]) poly[size++] = {mid_id(e), -1};
      }
      if (size == 3) {
        piece_tets[region[n[0]]].push_back({centre, n[kFace[f][0]], n[kFace[f][1]], n[kFace[f][2]]});
        piece_source[region[n[0]]].push_back(t);
        continue;
      }
      face_centre[f] = face_id({n[kFace[f][0]], n[kFace[f][1]], n[kFace[f][2]]});
      for (int s = 0; s < size; ++s) {
        const auto& p = poly[s];
        const auto& q = poly[(s + 1) % size];
        const int owner = region[n[p.second >= 0 ? p.second : q.second]];
        piece_tets[owner].push_back({centre, face_centre[f], p.first, q.first});
        piece_source[owner].push_back(t);
      }
    }
    if (!split_tet(t)) continue;
    for (int e = 0; e < 6; ++e) {
      const int i = kEdge[e][0], j = kEdge[e][1];
      if (region[n[i]] == region[n[j]]) continue;
      const auto [k1, k2] = off_edge(e);
      const int m = midpoint[te[e]];
      const std::array<std::array<int, 3>, 2> quad{{{m, face_centre[k1], centre}, {m, centre, face_centre[k2]}}};
      for (auto tri : quad) {
        // Facing away from vertex i: outward from i's cell.
        if (signed_volume_m3(mesh.nodes_m[n[i]], points[tri[0]], points[tri[1]], points[tri[2]]) < 0)
          std::swap(tri[1], tri[2]);
        FractureTriangle side_i{{points[tri[0]], points[tri[1]], points[tri[2]]}, region[n[i]], region[n[j]], t};
        FractureTriangle side_j{{points[tri[0]], points[tri[2]], points[tri[1]]}, region[n[j]], region[n[i]], t};
        out.fracture_triangles.push_back(side_i);
        out.fracture_triangles.push_back(side_j);
      }
      out.area_m2 += quad_area_m2[static_cast<std::size_t>(t) * 6 + e];  // the sum the bound was checked on
    }
  }

  // Compact each piece's nodes in order of first use.
  std::vector<int> local(points.size(), -1);
  out.pieces.resize(regions);
  for (int r = 0; r < regions; ++r) {
    Piece& piece = out.pieces[r];
    std::vector<int> used;
    piece.mesh.tets = std::move(piece_tets[r]);
    for (auto& tet : piece.mesh.tets)
      for (int& v : tet) {
        if (local[v] < 0) {
          local[v] = static_cast<int>(used.size());
          used.push_back(v);
        }
        v = local[v];
      }
    piece.mesh.nodes_m.reserve(used.size());
    for (int v : used) {
      piece.mesh.nodes_m.push_back(points[v]);
      local[v] = -1;
    }
    piece.source_tets = std::move(piece_source[r]);
    for (const auto& f : boundary_faces(piece.mesh)) piece.surface.push_back(f.nodes);
  }
  return out;
}

}  // namespace

FracturePattern fracture_pattern(const TetMesh& mesh, const std::vector<double>& energy_density_j_m3,
                                 double strain_energy_j, const PatternSettings& settings) {
  check_input(mesh, energy_density_j_m3, strain_energy_j, settings);
  FracturePattern none;
  const int nodes = static_cast<int>(mesh.nodes_m.size());
  const int tets = static_cast<int>(mesh.tets.size());
  if (tets == 0 || settings.max_pieces < 2) return none;
  const EdgeGraph g = edge_graph(mesh);
  check_connected(mesh, g);

  // Nodal density: the volume-weighted mean of the node's tetrahedra; nodal volume: a quarter of
  // each. Their product, the node's share of the strain energy, is the sampling weight.
  std::vector<double> volume_m3(nodes, 0), energy_j(nodes, 0);
  for (int t = 0; t < tets; ++t) {
    const double v = tet_volume_m3(mesh, t);
    for (int n : mesh.tets[t]) {
      volume_m3[n] += v / 4;
      energy_j[n] += v * energy_density_j_m3[t] / 4;
    }
  }
  std::vector<double> density(nodes, 0);
  double density_max = 0;
  for (int n = 0; n < nodes; ++n) {
    if (volume_m3[n] > 0) density[n] = energy_j[n] / volume_m3[n];
    density_max = std::max(density_max, density[n]);
  }
  const std::vector<int> seeds =
      settings.seed_nodes.empty() ? sample_seeds(energy_j, settings.seed, settings.max_pieces) : settings.seed_nodes;
  // A floor keeps k_i > 0 for a seed in a region of no energy (given seeds only).
  const double density_floor = std::max(density_max * 1e-12, std::numeric_limits<double>::min());
  std::vector<double> k;
  for (int s : seeds) k.push_back(std::pow(std::max(density[s], density_floor), settings.alpha));

  // Each tetrahedron's 6 interface quads, so that A_F of a labelling is a sum over its split ones.
  std::vector<double> quad_area_m2(static_cast<std::size_t>(tets) * 6);
  for (int t = 0; t < tets; ++t)
    for (int e = 0; e < 6; ++e) {
      double a = 0;
      for (const auto& tri : interface_quad(mesh, mesh.tets[t], e)) a += triangle_area_m2(tri[0], tri[1], tri[2]);
      quad_area_m2[static_cast<std::size_t>(t) * 6 + e] = a;
    }

  const double budget_j = settings.eta * strain_energy_j;
  RegionGrower grower(g, nodes);
  std::vector<int> region, accepted;
  int accepted_seeds = 0;
  const int most = std::min<int>(settings.max_pieces, static_cast<int>(seeds.size()));
  for (int s = 2; s <= most; ++s) {
    const std::vector<int> first(seeds.begin(), seeds.begin() + s);
    const std::vector<double> first_k(k.begin(), k.begin() + s);
    grower.grow(first, first_k, region);
    double area_m2 = 0;
    for (int t = 0; t < tets; ++t) {
      const auto& n = mesh.tets[t];
      for (int e = 0; e < 6; ++e)
        if (region[n[kEdge[e][0]]] != region[n[kEdge[e][1]]])
          area_m2 += quad_area_m2[static_cast<std::size_t>(t) * 6 + e];
    }
    if (settings.fracture_energy_j_m2 * area_m2 > budget_j) break;
    if (settings.min_piece_volume_m3 > 0) {  // by nodal volumes: the split moves little volume
      std::vector<double> region_m3(static_cast<std::size_t>(s), 0);
      for (int n = 0; n < nodes; ++n) region_m3[region[n]] += volume_m3[n];
      if (*std::min_element(region_m3.begin(), region_m3.end()) < settings.min_piece_volume_m3) break;
    }
    accepted.swap(region);
    accepted_seeds = s;
  }
  if (accepted_seeds < 2) return none;
  FracturePattern out = build_pattern(mesh, g, accepted, accepted_seeds, quad_area_m2);
  out.fracture_energy_j = settings.fracture_energy_j_m2 * out.area_m2;
  out.seeds = accepted_seeds;
  return out;
}

}  // namespace clatter::kernels::fracture
