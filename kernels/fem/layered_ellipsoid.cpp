// The layered mesher of flat ellipsoids (ellipsoid_mesh.hpp, mesh_layered_ellipsoid).
//
// Why prisms split by node number: a prism over the triangle (v0, v1, v2), v0 < v1 < v2, between
// layers j (bottom, B) and j + 1 (top, T) is the three tetrahedra
//   {B0, B1, B2, T2}, {B0, B1, T1, T2}, {B0, T0, T1, T2},
// whose quadrilateral faces are cut from the lower-numbered vertex's bottom node to the other's
// top node; the prism across that face cuts it the same way, so the mesh conforms. On the rim a
// column is one node (B = T there): the tetrahedra that repeat a node have no volume and are
// dropped, and what remains is the pyramid or tetrahedron the collapsed prism is.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "kernels/fem/ellipse_triangulation.hpp"
#include "kernels/fem/ellipsoid_mesh.hpp"
#include "kernels/fem/ellipsoid_parts.hpp"
#include "kernels/fem/mesh_quality.hpp"

namespace clatter::kernels::fem {

EllipsoidMesh mesh_layered_ellipsoid(const LayeredMeshSettings& s, const EllipsoidMeshBounds& bounds) {
  const auto& r = s.semi_axes_m;
  if (!(r[0] > 0 && r[1] > 0 && r[2] > 0 && s.edge_length_m > 0 && s.layers >= 1 && s.rim_rings >= 0 &&
        s.rim_spacing_fraction > 0 && s.rim_spacing_fraction <= 1 && s.rim_grading > 0))
    throw std::invalid_argument("mesh_layered_ellipsoid: semi-axes, edge length, layers, rim spacing and grading must "
                                "be positive, rim rings not negative (the rim spacing at most 1 h)");
  // The thin axis and the plane's two, in axis order.
  const int thin = static_cast<int>(std::min_element(r.begin(), r.end()) - r.begin());
  const int p = thin == 0 ? 1 : 0, q = thin == 2 ? 1 : 2;
  const double a = r[thin], b = r[p], c = r[q];
  const double h = s.edge_length_m, spacing = s.rim_spacing_fraction * h;
  RimBand band;
  band.spacing_m = spacing;
  const double deepest = std::min(0.5, 2 * spacing / b);
  for (int k = s.rim_rings - 1; k >= 0; --k) band.depths.push_back(deepest / std::pow(2.0, k));
  const double rho_inner = band.depths.empty() ? 1.0 : 1 - band.depths.back();

  // The size field inside the band: its spacing at the band, growing with the distance to it (to
  // first order (rho_inner - rho) / |grad rho|), capped at h.
  auto size_m = [&](double y, double z) {
    const double rho = std::hypot(y / b, z / c);
    if (rho < 1e-12) return h;
    const double grad = std::hypot(y / (b * b), z / (c * c)) / rho;
    return std::min(h, spacing + s.rim_grading * std::max(0.0, rho_inner - rho) / grad);
  };
  const EllipseTriangulation plane = triangulate_ellipse(b, c, size_m, band);

  // Nodes: every column's bottom and top (one node on the rim) first, so the surface nodes are the
  // first ones, then the inner layers.
  const int n_layers = s.layers;
  const std::size_t n_plane = plane.points_m.size();
  std::vector<std::vector<int>> column(n_plane);
  std::vector<double> half_thickness(n_plane, 0.0);
  LinearMesh linear;
  struct NodeAt {
    std::size_t v;  // the plane's point
    double f;       // place in the thickness, -1 (bottom) to 1 (top)
  };
  std::vector<NodeAt> node_at;
  auto add = [&](std::size_t v, int j) {
    node_at.push_back({v, -1 + 2.0 * j / n_layers});
    std::array<double, 3> x{};
    x[p] = plane.points_m[v][0];
    x[q] = plane.points_m[v][1];
    x[thin] = half_thickness[v] * (-1 + 2.0 * j / n_layers);
    linear.points.push_back(x);
    return static_cast<int>(linear.points.size() - 1);
  };
  for (std::size_t v = 0; v < n_plane; ++v) {
    column[v].assign(static_cast<std::size_t>(n_layers + 1), -1);
    if (plane.on_rim[v]) {
      const int node = add(v, 0);
      std::fill(column[v].begin(), column[v].end(), node);
      continue;
    }
    const double y = plane.points_m[v][0] / b, z = plane.points_m[v][1] / c;
    half_thickness[v] = a * std::sqrt(std::max(0.0, 1 - y * y - z * z));
    column[v][0] = add(v, 0);
    column[v][static_cast<std::size_t>(n_layers)] = add(v, n_layers);
  }
  const std::size_t n_surface = linear.points.size();
  for (std::size_t v = 0; v < n_plane; ++v)
    if (!plane.on_rim[v])
      for (int j = 1; j < n_layers; ++j) column[v][static_cast<std::size_t>(j)] = add(v, j);

  for (auto t : plane.triangles) {
    std::sort(t.begin(), t.end());
    for (int j = 0; j < n_layers; ++j) {
      auto B = [&](int k) { return column[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])][static_cast<std::size_t>(j)]; };
      auto T = [&](int k) { return column[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])][static_cast<std::size_t>(j + 1)]; };
      for (const std::array<int, 4>& tet : {std::array<int, 4>{B(0), B(1), B(2), T(2)}, std::array<int, 4>{B(0), B(1), T(1), T(2)},
                                            std::array<int, 4>{B(0), T(0), T(1), T(2)}}) {
        auto sorted = tet;
        std::sort(sorted.begin(), sorted.end());
        if (std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) linear.tets.push_back(tet);
      }
    }
  }
  if (linear.tets.empty()) throw MeshError("layered mesher", "no tetrahedra (the ellipse's triangulation is empty)");
  // Mid-nodes on the map (y, z, f) -> (y, z, f t(y, z)), f the layer's place in [-1, 1] and t the
  // half thickness: the edge's midpoint in (y, z) (in the band, in (rho, theta)) and in f, then
  // mapped. Surface edges (f = +-1, or on the rim) land on the ellipsoid. The nearest point would
  // move a mid-node near the rim sideways by the ring's sagitta, as far as the band's thinnest
  // rings are wide, and fold them.
  EllipsoidMesh out = quadratic_mesh(linear, n_surface, [&](int na, int nb, bool) {
    const auto& A = node_at[static_cast<std::size_t>(na)];
    const auto& B = node_at[static_cast<std::size_t>(nb)];
    const auto& pa = plane.points_m[A.v];
    const auto& pb = plane.points_m[B.v];
    double y = 0.5 * (pa[0] + pb[0]), z = 0.5 * (pa[1] + pb[1]);
    const double ring_a = plane.ring_rho[A.v], ring_b = plane.ring_rho[B.v];
    if (ring_a > 0 && ring_b > 0) {
      // Both ends on the band's rings: the band is the image of a grid in (rho, theta), and every
      // edge in it takes its mid-node from that map, so the ring edges follow their ellipses and
      // the others curve alike (curving the ring edges alone folds the thin rings near the rim).
      const double ta = std::atan2(pa[1] / c, pa[0] / b);
      double tb = std::atan2(pb[1] / c, pb[0] / b);
      if (tb - ta > std::numbers::pi) tb -= 2 * std::numbers::pi;
      if (ta - tb > std::numbers::pi) tb += 2 * std::numbers::pi;
      const double rho = 0.5 * (ring_a + ring_b), theta = 0.5 * (ta + tb);
      y = rho * b * std::cos(theta);
      z = rho * c * std::sin(theta);
    }
    // A rim node's column is one node: it takes the other end's place in the thickness.
    const double f = plane.on_rim[A.v] ? B.f : plane.on_rim[B.v] ? A.f : 0.5 * (A.f + B.f);
    std::array<double, 3> x{};
    x[p] = y;
    x[q] = z;
    x[thin] = f * a * std::sqrt(std::max(0.0, 1 - (y / b) * (y / b) - (z / c) * (z / c)));
    return x;
  });
  out.quality = mesh_quality(out.mesh);
  out.quality.edge_length_m = h;
  EllipsoidMeshBounds jacobian_only = bounds;
  jacobian_only.max_radius_edge = std::numeric_limits<double>::infinity();
  jacobian_only.min_dihedral_deg = 0;
  check_bounds(out.quality, jacobian_only);
  return out;
}

}  // namespace clatter::kernels::fem
