// Edge flips and smoothing of the ellipsoid's surface triangulation (no TetGen here).
//
// Why: the boundary tetrahedra keep the surface triangles (TetGen -Y), so a needle triangle makes a
// bad tetrahedron that -q cannot repair. The smoothed octahedron has them where its
// topology does not fit the shape (the rim of a flat ellipsoid), and bisection may halve a
// triangle's angles. Flips towards the Delaunay triangulation and a size-weighted smoothing fix
// both without adding vertices.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "kernels/fem/ellipsoid_parts.hpp"

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;
using Face = std::array<int, 3>;

P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const P3& a) { return std::sqrt(dot(a, a)); }
long long edge_key(int a, int b) { return static_cast<long long>(std::min(a, b)) << 32 | std::max(a, b); }

// The angle at a in the triangle a, b, c.
double angle_rad(const P3& a, const P3& b, const P3& c) {
  const P3 u = sub(b, a), v = sub(c, a);
  return std::atan2(norm(cross(u, v)), dot(u, v));
}

// The triangle's smallest angle, or -1 where its normal strays more than 60 degrees from the
// ellipsoid's at one of its vertices: a fold, never traded for a better angle (and a surface that
// overlaps itself, which TetGen cannot mesh, has one).
double face_quality(const P3& r, const std::vector<P3>& x, const Face& f) {
  const P3 &a = x[f[0]], &b = x[f[1]], &c = x[f[2]];
  const P3 n = cross(sub(b, a), sub(c, a));
  for (const P3* v : {&a, &b, &c}) {
    const P3 g{(*v)[0] / (r[0] * r[0]), (*v)[1] / (r[1] * r[1]), (*v)[2] / (r[2] * r[2])};
    if (!(dot(n, g) > 0.5 * norm(n) * norm(g))) return -1;
  }
  return std::min({angle_rad(a, b, c), angle_rad(b, c, a), angle_rad(c, a, b)});
}

// Every face stays in one octant (as the octahedron's and their halves do), so the three
// principal ellipses remain polylines of vertices: a flat ellipsoid's rim keeps its vertices on
// the rim, where no edge crosses it (an edge across the rim's apex, c^2/a in radius, would have
// to be about that short).
bool crosses_plane(const P3& a, const P3& b) { return a[0] * b[0] < 0 || a[1] * b[1] < 0 || a[2] * b[2] < 0; }

// Faces by edge: the two faces on each (closed surface).
using EdgeFaces = std::unordered_map<long long, std::array<int, 2>>;

EdgeFaces edge_faces(const std::vector<Face>& faces) {
  EdgeFaces out;
  out.reserve(2 * faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = out.try_emplace(edge_key(faces[f][k], faces[f][(k + 1) % 3]), std::array<int, 2>{-1, -1});
      it->second[it->second[0] < 0 ? 0 : 1] = static_cast<int>(f);
    }
  return out;
}

void replace_face(EdgeFaces& e, int a, int b, int from, int to) {
  auto& pair = e.at(edge_key(a, b));
  pair[pair[0] == from ? 0 : 1] = to;
}

// Flips edge k of face f (a, b, c) with the face g (b, a, d) across it, to (a, d, c) and (d, b, c),
// when the angles facing the edge sum above pi (not Delaunay), the new edge is not there yet and
// crosses no coordinate plane, neither end drops below four edges (a vertex of three is the corner
// of a tetrahedron on three boundary faces, which folds when curved) and the smaller of the four
// angles grows.
bool try_flip(SurfaceTriangulation& s, const EdgeRule& rule, EdgeFaces& e, std::vector<int>& valence, int f, int k) {
  const P3& r = rule.semi_axes_m;
  const Face fa = s.faces[f];
  const int a = fa[k], b = fa[(k + 1) % 3], c = fa[(k + 2) % 3];
  const auto pair = e.at(edge_key(a, b));
  const int g = pair[0] == f ? pair[1] : pair[0];
  const Face& fg = s.faces[g];
  const int d = fg[0] != a && fg[0] != b ? fg[0] : fg[1] != a && fg[1] != b ? fg[1] : fg[2];
  const auto& x = s.vertices_m;
  if (angle_rad(x[c], x[a], x[b]) + angle_rad(x[d], x[a], x[b]) <= std::numbers::pi * (1 + 1e-12)) return false;
  if (e.count(edge_key(c, d)) || valence[a] <= 4 || valence[b] <= 4 || crosses_plane(x[c], x[d])) return false;
  const Face nf{a, d, c}, ng{d, b, c};
  if (std::min(face_quality(r, x, nf), face_quality(r, x, ng)) <= std::min(face_quality(r, x, fa), face_quality(r, x, fg)))
    return false;
  e.erase(edge_key(a, b));
  e.emplace(edge_key(c, d), std::array<int, 2>{f, g});
  replace_face(e, a, d, g, f);
  replace_face(e, b, c, f, g);
  s.faces[f] = nf;
  s.faces[g] = ng;
  --valence[a];
  --valence[b];
  ++valence[c];
  ++valence[d];
  return true;
}

void flip_edges(SurfaceTriangulation& s, const EdgeRule& rule) {
  EdgeFaces e = edge_faces(s.faces);
  std::vector<int> valence(s.vertices_m.size(), 0);
  for (const auto& f : s.faces)
    for (int v : f) ++valence[v];
  // Each flip raises the smallest angle of its pair, so passes end; 50 is a guard.
  for (int pass = 0; pass < 50; ++pass) {
    bool flipped = false;
    for (std::size_t f = 0; f < s.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) flipped = try_flip(s, rule, e, valence, static_cast<int>(f), k) || flipped;
    if (!flipped) return;
  }
}

// Gauss-Seidel in vertex order: each vertex to the centroid of its faces' centroids, weighted by
// area / spacing^4 (the density under which centroidal cells in 2-D have that spacing; the
// spacing the mean edge at the vertex, so the refinement's grading stays), projected onto the
// ellipsoid (one on a principal ellipse along it); kept only where no face folds that did not, no edge turns too coarse that was not
// (a vertex sliding off a rim would leave edges across it) and the smallest angle does not shrink.
void smooth(SurfaceTriangulation& s, const EdgeRule& rule, int sweeps) {
  const P3& r = rule.semi_axes_m;
  std::vector<std::vector<int>> star(s.vertices_m.size());
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (int v : s.faces[f]) star[v].push_back(static_cast<int>(f));
  std::vector<double> spacing(s.vertices_m.size(), 0);
  for (const Face& t : s.faces)
    for (int k = 0; k < 3; ++k)
      spacing[t[k]] += norm(sub(s.vertices_m[t[k]], s.vertices_m[t[(k + 1) % 3]])) / static_cast<double>(star[t[k]].size());
  auto worst = [&](std::size_t v) {
    std::tuple<int, int, double> q{0, 0, 4};
    for (int f : star[v]) {
      const Face& t = s.faces[f];
      const P3 &a = s.vertices_m[t[0]], &b = s.vertices_m[t[1]], &c = s.vertices_m[t[2]];
      std::get<0>(q) -= face_quality(r, s.vertices_m, t) < 0;
      for (int k = 0; k < 3; ++k)
        if (t[k] == static_cast<int>(v)) std::get<1>(q) -= rule.too_coarse(s.vertices_m[t[k]], s.vertices_m[t[(k + 1) % 3]]);
      std::get<2>(q) = std::min({std::get<2>(q), angle_rad(a, b, c), angle_rad(b, c, a), angle_rad(c, a, b)});
    }
    return q;
  };
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (std::size_t v = 0; v < star.size(); ++v) {
      P3 sum{0, 0, 0};
      double weight = 0;
      for (int f : star[v]) {
        const Face& t = s.faces[f];
        const P3 &a = s.vertices_m[t[0]], &b = s.vertices_m[t[1]], &c = s.vertices_m[t[2]];
        const double h = (spacing[t[0]] + spacing[t[1]] + spacing[t[2]]) / 3;
        const double w = norm(cross(sub(b, a), sub(c, a))) / (h * h * h * h);
        for (int i = 0; i < 3; ++i) sum[i] += w * (a[i] + b[i] + c[i]) / 3;
        weight += w;
      }
      const P3 old = s.vertices_m[v];
      const auto before = worst(v);
      P3 next{sum[0] / weight, sum[1] / weight, sum[2] / weight};
      for (int i = 0; i < 3; ++i)
        if (old[i] == 0) next[i] = 0;  // a vertex of a principal ellipse stays on it
      s.vertices_m[v] = nearest_on_ellipsoid(r, next);
      if (worst(v) < before) s.vertices_m[v] = old;
    }
}

}  // namespace

bool flip_surface_edge(SurfaceTriangulation& s, int a, int b) {
  int f = -1, g = -1, c = -1, d = -1, k_f = 0;
  for (std::size_t i = 0; i < s.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int p = s.faces[i][k], q = s.faces[i][(k + 1) % 3];
      if ((p == a && q == b) || (p == b && q == a)) {
        (f < 0 ? f : g) = static_cast<int>(i);
        (c < 0 ? c : d) = s.faces[i][(k + 2) % 3];
        if (g < 0) k_f = k;
      }
    }
  if (g < 0 || d < 0) return false;
  for (const auto& face : s.faces)
    for (int k = 0; k < 3; ++k)
      if ((face[k] == c && face[(k + 1) % 3] == d) || (face[k] == d && face[(k + 1) % 3] == c)) return false;
  // f = (p, q, c) along its edge k_f, g = (q, p, d): to (p, d, c) and (d, q, c).
  const int p = s.faces[f][k_f], q = s.faces[f][(k_f + 1) % 3];
  s.faces[f] = {p, d, c};
  s.faces[g] = {d, q, c};
  return true;
}

void improve_surface(SurfaceTriangulation& s, const EdgeRule& rule) {
  for (int round = 0; round < 3; ++round) {
    flip_edges(s, rule);
    smooth(s, rule, 5);
  }
  flip_edges(s, rule);
}

}  // namespace clatter::kernels::fem
