// Curvature-adaptive refinement of the ellipsoid's surface triangulation (no TetGen here).
//
// The rule, per edge of length L: the sagitta s (how far its mid-node moves from the chord's
// midpoint onto the ellipsoid) at most k/8 min(L, kThin^2 k T), T the chord through the body along
// the normal there (the local thickness); and no edge much longer than its neighbours' (isotropy,
// below), none above 1.5 h. Why: TetGen may not split the preserved surface (-Y), so
// the boundary tetrahedra keep the surface's edges, and a curved element folds (det J <= 0) once
// its mid-node moves by a sizeable part of its height, which is about L in a thick body and at
// most T in a thin one. On a sphere s = L^2 / (8 R), so the rule is the suggested L <= k R there;
// where the body is thin it is L <= kThin k sqrt(R T) instead, which is what keeps the rim of a
// flat ellipsoid affordable: at the rim's parabolic edge (apex radius R0 = c^2/a) an edge of
// length L from the apex has s/T = sqrt(2)/8 whatever L, while k R0 there would ask for edges of
// c^2/a all along the rim (a 1:20:20 one: 2500 of them per row). Measuring s instead of bounding it by the
// smallest curvature radius also asks nothing where the curvature is high across an edge's
// direction but not along it (a cigar's waist, along its axis).
// Why bisection: longest-edge bisection keeps the triangles' angles bounded below (Rivara) and
// keeps every edge that is short enough, so the spacing grades itself from the fine rows (each
// neighbour at most halves); the volume then grades from this surface to h inside through
// TetGen's -q refinement (each inserted point is a bad tetrahedron's circumcentre, so sizes grow
// away from the surface at the rate the radius-edge bound allows), with no size function to give.
#include "kernels/fem/ellipsoid_parts.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace clatter::kernels::fem {
namespace {

using P3 = std::array<double, 3>;

// The thin part of the rule allows kThin^2 more: edges from a rim's parabolic apex have s / T =
// sqrt(2) / 8 = 0.177 whatever their length, which k = 1 alone (0.125) would cut without end.
constexpr double kThin = 1.3;
// Isotropy: an edge longer than this times the least length L* allowed at either end (below).
constexpr double kIsotropy = 1.5;

double distance_m(const P3& a, const P3& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

P3 chord_midpoint(const P3& a, const P3& b) { return {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])}; }

// The triangle's normal within 90 degrees of the ellipsoid's at each of its vertices.
bool faces_out(const P3& r, const P3& a, const P3& b, const P3& c) {
  const P3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const P3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  for (const P3* x : {&a, &b, &c})
    if (!(n[0] * (*x)[0] / (r[0] * r[0]) + n[1] * (*x)[1] / (r[1] * r[1]) + n[2] * (*x)[2] / (r[2] * r[2]) > 0)) return false;
  return true;
}

// Each edge once (numbered in order of first use, so deterministic) and, for each face, the
// numbers of its edges k = (f[k], f[k+1]).
struct EdgeTable {
  std::vector<std::array<int, 2>> ends;
  std::vector<double> length_m;
  std::vector<std::array<int, 3>> of_face;
};

EdgeTable edge_table(const SurfaceTriangulation& s) {
  EdgeTable t;
  std::unordered_map<long long, int> number;
  number.reserve(2 * s.faces.size());
  t.of_face.resize(s.faces.size());
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(s.faces[f][k], s.faces[f][(k + 1) % 3]), b = std::max(s.faces[f][k], s.faces[f][(k + 1) % 3]);
      const auto [it, inserted] = number.try_emplace(static_cast<long long>(a) << 32 | b, static_cast<int>(t.ends.size()));
      if (inserted) {
        t.ends.push_back({a, b});
        t.length_m.push_back(distance_m(s.vertices_m[a], s.vertices_m[b]));
      }
      t.of_face[f][k] = it->second;
    }
  return t;
}

// The face's longest edge (local number), ties to the lower edge number.
int longest(const EdgeTable& t, std::size_t f) {
  int best = 0;
  for (int k = 1; k < 3; ++k) {
    const int e = t.of_face[f][k], b = t.of_face[f][best];
    if (t.length_m[e] > t.length_m[b] || (t.length_m[e] == t.length_m[b] && e < b)) best = k;
  }
  return best;
}

// Until nothing changes, marks the longest edge of every face with a marked edge (so each face is
// cut through its longest edge first: Rivara).
void close_marks(const SurfaceTriangulation& s, const EdgeTable& t, std::vector<char>& marked) {
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      const auto& e = t.of_face[f];
      const int l = e[longest(t, f)];
      if (!marked[l] && (marked[e[0]] || marked[e[1]] || marked[e[2]])) marked[l] = changed = true;
    }
  }
}

// The edges the rule finds too coarse, closed as above.
std::vector<char> marked_edges(const SurfaceTriangulation& s, const EdgeTable& t, const EdgeRule& rule) {
  std::vector<char> marked(t.ends.size(), 0);
  for (std::size_t e = 0; e < t.ends.size(); ++e)
    marked[e] = rule.too_coarse(s.vertices_m[t.ends[e][0]], s.vertices_m[t.ends[e][1]]);
  // Isotropy: where the rule allows long edges one way (along a flat ellipsoid's rim, with little
  // curvature) but short ones another (across it), rows of slivers would be the faces of
  // tetrahedra TetGen cannot improve (-Y). Each edge tells the curvature radius along it, R =
  // L^2 / (8 s), hence the length L* = k min(R, kThin sqrt(R T)) the rule allows that way; an edge
  // longer than kIsotropy times the least L* at either end is cut too.
  std::vector<double> allowed(s.vertices_m.size(), rule.max_edge_m);
  for (std::size_t e = 0; e < t.ends.size(); ++e) {
    const P3 &a = s.vertices_m[t.ends[e][0]], &b = s.vertices_m[t.ends[e][1]];
    const P3 m = chord_midpoint(a, b), p = nearest_on_ellipsoid(rule.semi_axes_m, m);
    const double sagitta = distance_m(m, p);
    if (!(sagitta > 0)) continue;
    const double radius = t.length_m[e] * t.length_m[e] / (8 * sagitta);
    const double length = rule.k * std::min(radius, kThin * std::sqrt(radius * normal_chord_m(rule.semi_axes_m, p)));
    for (int v : t.ends[e]) allowed[v] = std::min(allowed[v], length);
  }
  // Never below 8 R / k^2 (R the smallest curvature radius): where the rule bounds edges across
  // the rim's apex only (edges from the apex of length L have s/L = sqrt(2 R0 / L) / 4, fine from
  // L = 8 R0 / k^2 on), an edge across it, off the apex, would ask for L* ~ k R0 along the whole
  // rim, and the isotropy would cut its neighbours down to that, pass after pass.
  for (std::size_t v = 0; v < allowed.size(); ++v)
    allowed[v] = std::max(allowed[v], 8 * min_curvature_radius_m(rule.semi_axes_m, s.vertices_m[v]) / (rule.k * rule.k));
  for (std::size_t e = 0; e < t.ends.size(); ++e)
    if (t.length_m[e] > kIsotropy * std::min(allowed[t.ends[e][0]], allowed[t.ends[e][1]])) marked[e] = 1;
  close_marks(s, t, marked);
  return marked;
}

// An edge's new vertex: the point nearest to the chord's midpoint, about halfway along the
// surface. (The ray from the centre through it is biased towards a cigar's tip, and would cut
// an edge there into a long and a short one pass after pass; it is the fallback where the
// nearest point, off to one side of a coarse edge, would turn a half face inside out.)
P3 new_vertex(const SurfaceTriangulation& s, const P3& r, const std::array<int, 2>& ends, const std::vector<int>& opposite) {
  const P3 &a = s.vertices_m[ends[0]], &b = s.vertices_m[ends[1]];
  const P3 m = nearest_on_ellipsoid(r, chord_midpoint(a, b));
  for (int c : opposite) {
    const P3& x = s.vertices_m[c];
    // Either orientation of (a, b, c) is a face: the halves must face the way it does.
    const bool ccw = faces_out(r, a, b, x);
    if (ccw ? !(faces_out(r, a, m, x) && faces_out(r, m, b, x)) : !(faces_out(r, m, a, x) && faces_out(r, b, m, x)))
      return onto_ellipsoid(r, chord_midpoint(a, b));
  }
  return m;
}

// Cuts each face with marked edges through its longest edge's new vertex, then each half again
// through the new vertex of its other marked edge; orientation is kept.
void bisect_marked(SurfaceTriangulation& s, const EdgeTable& t, const std::vector<char>& marked, const P3& r) {
  std::vector<std::vector<int>> opposite(t.ends.size());
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) opposite[t.of_face[f][k]].push_back(s.faces[f][(k + 2) % 3]);
  std::vector<int> mid(t.ends.size(), -1);
  for (std::size_t e = 0; e < t.ends.size(); ++e)
    if (marked[e]) {
      mid[e] = static_cast<int>(s.vertices_m.size());
      s.vertices_m.push_back(new_vertex(s, r, t.ends[e], opposite[e]));
    }
  std::vector<std::array<int, 3>> faces;
  faces.reserve(3 * s.faces.size());
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const int l = longest(t, f);
    const int e01 = t.of_face[f][l], e12 = t.of_face[f][(l + 1) % 3], e20 = t.of_face[f][(l + 2) % 3];
    if (!marked[e01]) {
      faces.push_back(s.faces[f]);
      continue;
    }
    const int p0 = s.faces[f][l], p1 = s.faces[f][(l + 1) % 3], p2 = s.faces[f][(l + 2) % 3], m = mid[e01];
    if (marked[e20]) {
      faces.push_back({p0, m, mid[e20]});
      faces.push_back({m, p2, mid[e20]});
    } else {
      faces.push_back({p0, m, p2});
    }
    if (marked[e12]) {
      faces.push_back({m, p1, mid[e12]});
      faces.push_back({m, mid[e12], p2});
    } else {
      faces.push_back({m, p1, p2});
    }
  }
  s.faces.swap(faces);
}

}  // namespace

double normal_chord_m(const P3& r, const P3& x) {
  // Along the inward normal -g/|g|, g = D x, D = diag(1 / r^2): |x - t g/|g||_D = 1 at
  // t = 2 |g|^3 / (g . D g).
  double gg = 0, gdg = 0;
  for (int i = 0; i < 3; ++i) {
    const double g = x[i] / (r[i] * r[i]);
    gg += g * g;
    gdg += g * g / (r[i] * r[i]);
  }
  return 2 * gg * std::sqrt(gg) / gdg;
}

bool EdgeRule::too_coarse(const P3& a, const P3& b) const {
  const double length = distance_m(a, b);
  if (length > max_edge_m) return true;
  const P3 m = chord_midpoint(a, b), p = nearest_on_ellipsoid(semi_axes_m, m);
  return distance_m(m, p) > k / 8 * std::min(length, kThin * kThin * k * normal_chord_m(semi_axes_m, p));
}

double min_curvature_radius_m(const P3& r, const P3& x) {
  // kappa(t) = t^T D t / |D x| for unit tangents t, D = diag(1 / r^2): the largest over the
  // tangent plane from the 2 x 2 eigenproblem in an orthonormal tangent basis.
  const P3 d{1 / (r[0] * r[0]), 1 / (r[1] * r[1]), 1 / (r[2] * r[2])};
  const P3 g{d[0] * x[0], d[1] * x[1], d[2] * x[2]};
  const double g_norm = std::hypot(g[0], g[1], g[2]);
  const P3 n{g[0] / g_norm, g[1] / g_norm, g[2] / g_norm};
  const int axis = std::abs(n[0]) <= std::abs(n[1]) && std::abs(n[0]) <= std::abs(n[2]) ? 0 : std::abs(n[1]) <= std::abs(n[2]) ? 1 : 2;
  P3 e1{0, 0, 0};
  e1[axis] = 1;
  const double along = e1[axis] * n[axis];
  for (int i = 0; i < 3; ++i) e1[i] -= along * n[i];
  const double e1_norm = std::hypot(e1[0], e1[1], e1[2]);
  for (double& c : e1) c /= e1_norm;
  const P3 e2{n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]};
  double m11 = 0, m22 = 0, m12 = 0;
  for (int i = 0; i < 3; ++i) {
    m11 += d[i] * e1[i] * e1[i];
    m22 += d[i] * e2[i] * e2[i];
    m12 += d[i] * e1[i] * e2[i];
  }
  const double largest = 0.5 * (m11 + m22) + std::hypot(0.5 * (m11 - m22), m12);
  return g_norm / largest;
}

void bisect_surface_edges(SurfaceTriangulation& s, const EdgeRule& rule, const std::vector<std::array<int, 2>>& edges) {
  const EdgeTable t = edge_table(s);
  std::unordered_map<long long, int> number;
  for (std::size_t e = 0; e < t.ends.size(); ++e) number[static_cast<long long>(t.ends[e][0]) << 32 | t.ends[e][1]] = static_cast<int>(e);
  std::vector<char> marked(t.ends.size(), 0);
  for (const auto& [a, b] : edges) {
    const auto it = number.find(static_cast<long long>(std::min(a, b)) << 32 | std::max(a, b));
    if (it != number.end()) marked[it->second] = 1;
  }
  close_marks(s, t, marked);
  bisect_marked(s, t, marked, rule.semi_axes_m);
}

bool refine_surface(SurfaceTriangulation& s, const EdgeRule& rule) {
  // Each pass halves every marked edge; no edge need be shorter than about the smallest
  // curvature radius c^2/a: log2 of (h / that) passes. 200 is never reached.
  for (int pass = 0; pass < 200; ++pass) {
    const EdgeTable t = edge_table(s);
    const std::vector<char> marked = marked_edges(s, t, rule);
    if (std::find(marked.begin(), marked.end(), 1) == marked.end()) return pass > 0;
    bisect_marked(s, t, marked, rule.semi_axes_m);
  }
  throw MeshError("the curvature refinement of the surface did not end");
}

}  // namespace clatter::kernels::fem
