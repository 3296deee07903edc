// CGAL's 2D constrained Delaunay refinement (Shewchuk's / Ruppert's algorithm) with a size field:
// CGAL's Delaunay_mesh_size_criteria_2 bounds every edge by one constant; here the bound is the
// size field at the triangle's centroid, so the triangulation grades toward the rim.
#include "kernels/fem/ellipse_triangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <algorithm>
#include <map>
#include <numbers>
#include <stdexcept>

namespace clatter::kernels::fem {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
using Fb = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds>;
using Point = Cdt::Point;
using SizeField = std::function<double(double, double)>;

// CGAL's size criteria with the bound taken from the field: a triangle is imperatively bad while
// its longest edge exceeds the field at its centroid, bad while its smallest angle is below the
// aspect bound (B = sin^2 of the smallest angle).
class SizeFieldCriteria : public CGAL::Delaunay_mesh_size_criteria_2<Cdt> {
 public:
  using Base = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
  SizeFieldCriteria(double aspect_bound, const SizeField* size) : Base(aspect_bound, 1.0), size_(size) {}

  class Is_bad : public Base::Is_bad {
   public:
    Is_bad(double aspect_bound, const SizeField* size, const Kernel& kernel)
        : Base::Is_bad(aspect_bound, 1.0, kernel), size_(size) {}
    using Base::Is_bad::operator();
    CGAL::Mesh_2::Face_badness operator()(const Cdt::Face_handle& fh, Quality& q) const {
      const Point& pa = fh->vertex(0)->point();
      const Point& pb = fh->vertex(1)->point();
      const Point& pc = fh->vertex(2)->point();
      const double a = CGAL::to_double(CGAL::squared_distance(pb, pc));
      const double b = CGAL::to_double(CGAL::squared_distance(pc, pa));
      const double c = CGAL::to_double(CGAL::squared_distance(pa, pb));
      const double longest = std::max({a, b, c});
      const double second = a + b + c - longest - std::min({a, b, c});
      const double s = (*size_)((pa.x() + pb.x() + pc.x()) / 3, (pa.y() + pb.y() + pc.y()) / 3);
      q.second = longest / (s * s);
      if (q.size() > 1) {
        q.first = 1;
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      const double area2 = 2 * CGAL::to_double(CGAL::area(pa, pb, pc));
      q.first = area2 * area2 / (longest * second);
      return q.sine() < this->B ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }

   private:
    const SizeField* size_;
  };
  Is_bad is_bad_object() const { return Is_bad(this->bound(), size_, this->traits); }

 private:
  const SizeField* size_;
};

std::array<double, 2> on_ellipse(double b, double c, double theta) { return {b * std::cos(theta), c * std::sin(theta)}; }

// Rim points at equal arc length, at most size_m apart (the field sampled along the rim).
std::vector<std::array<double, 2>> rim_points(double b, double c, const SizeField& size_m) {
  constexpr int kTable = 1 << 14;
  std::vector<double> arc(kTable + 1, 0.0);
  double smallest = HUGE_VAL;
  for (int i = 1; i <= kTable; ++i) {
    const auto p = on_ellipse(b, c, 2 * std::numbers::pi * (i - 1) / kTable);
    const auto q = on_ellipse(b, c, 2 * std::numbers::pi * i / kTable);
    arc[i] = arc[i - 1] + std::hypot(q[0] - p[0], q[1] - p[1]);
    smallest = std::min(smallest, size_m(q[0], q[1]));
  }
  if (!(smallest > 0)) throw std::invalid_argument("triangulate_ellipse: the size field is not positive on the rim");
  const int n = std::max(8, static_cast<int>(std::ceil(arc[kTable] / smallest)));
  std::vector<std::array<double, 2>> points;
  int j = 0;
  for (int k = 0; k < n; ++k) {
    const double s = arc[kTable] * k / n;
    while (arc[j + 1] < s) ++j;
    const double t = (j + (s - arc[j]) / (arc[j + 1] - arc[j])) / kTable;
    points.push_back(on_ellipse(b, c, 2 * std::numbers::pi * t));
  }
  return points;
}

// Two closed rings of points ordered by angle (outer, inner; their angles ascending from the same
// start) joined by triangles: the classic stitch, each step advancing on the ring whose next point
// comes first.
void stitch(const std::vector<int>& outer, const std::vector<double>& outer_angle, const std::vector<int>& inner,
            const std::vector<double>& inner_angle, std::vector<std::array<int, 3>>& triangles) {
  const std::size_t n = outer.size(), m = inner.size();
  auto angle = [](const std::vector<double>& a, std::size_t i) {
    return i < a.size() ? a[i] : a[i - a.size()] + 2 * std::numbers::pi;
  };
  std::size_t i = 0, j = 0;
  while (i < n || j < m) {
    const bool advance_outer = j == m || (i < n && angle(outer_angle, i + 1) <= angle(inner_angle, j + 1));
    if (advance_outer) {
      triangles.push_back({outer[i % n], outer[(i + 1) % n], inner[j % m]});
      ++i;
    } else {
      triangles.push_back({outer[i % n], inner[(j + 1) % m], inner[j % m]});
      ++j;
    }
  }
}

double parametric_angle(double b, double c, double y, double z) {
  const double t = std::atan2(z / c, y / b);
  return t < 0 ? t + 2 * std::numbers::pi : t;
}

}  // namespace

EllipseTriangulation triangulate_ellipse(double b_m, double c_m, const SizeField& size_m, const RimBand& band) {
  if (!(b_m > 0 && c_m > 0)) throw std::invalid_argument("triangulate_ellipse: semi-axes must be positive");
  for (std::size_t k = 0; k < band.depths.size(); ++k)
    if (!(band.depths[k] > 0 && band.depths[k] < 1 && (k == 0 || band.depths[k] > band.depths[k - 1])))
      throw std::invalid_argument("triangulate_ellipse: the band's depths must rise within (0, 1)");
  // The rim, and the band's rings: the rim's points scaled by rho = 1 - depth.
  const auto rim = rim_points(b_m, c_m, band.depths.empty() ? size_m : [&](double, double) { return band.spacing_m; });
  const std::size_t n = rim.size();
  std::vector<double> rim_angle;
  for (const auto& p : rim) rim_angle.push_back(parametric_angle(b_m, c_m, p[0], p[1]));
  EllipseTriangulation out;
  std::vector<std::vector<int>> ring;  // the band's rings by index into out.points_m, rim first
  for (std::size_t k = 0; k < band.depths.size(); ++k) {
    const double rho = k == 0 ? 1.0 : 1 - band.depths[k - 1];
    ring.emplace_back();
    for (const auto& p : rim) {
      ring.back().push_back(static_cast<int>(out.points_m.size()));
      out.points_m.push_back({rho * p[0], rho * p[1]});
      out.on_rim.push_back(k == 0);
      out.ring_rho.push_back(rho);
    }
  }
  for (std::size_t k = 0; k + 1 < ring.size(); ++k)
    for (std::size_t i = 0; i < n; ++i) {
      const int a = ring[k][i], b = ring[k][(i + 1) % n], c = ring[k + 1][(i + 1) % n], d = ring[k + 1][i];
      out.triangles.push_back({a, b, c});
      out.triangles.push_back({a, c, d});
    }

  // CGAL inside the innermost ring (or the rim, without a band).
  const double rho_inner = band.depths.empty() ? 1.0 : 1 - band.depths.back();
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  for (const auto& p : rim) handles.push_back(cdt.insert(Point(rho_inner * p[0], rho_inner * p[1])));
  for (std::size_t k = 0; k < n; ++k) cdt.insert_constraint(handles[k], handles[(k + 1) % n]);
  CGAL::refine_Delaunay_mesh_2(cdt, SizeFieldCriteria(0.125, &size_m));

  // Points on a constrained edge are the inner ring's (the refinement may split its edges): on
  // the rim they go onto the ellipse, along the ray from the centre (a move of the chord's
  // sagitta, outward); inside a band they stay where they are, on the ring's chords.
  std::map<Cdt::Vertex_handle, int> index;
  const std::size_t offset = out.points_m.size();
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    index.emplace(v, static_cast<int>(out.points_m.size()));
    out.points_m.push_back({v->point().x(), v->point().y()});
    out.on_rim.push_back(0);
    out.ring_rho.push_back(0);
  }
  for (const auto& v : handles) out.ring_rho[static_cast<std::size_t>(index.at(v))] = rho_inner;
  std::vector<char> on_ring(out.points_m.size(), 0);
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e)
    if (cdt.is_constrained(*e))
      for (int k : {Cdt::cw(e->second), Cdt::ccw(e->second)}) on_ring[static_cast<std::size_t>(index.at(e->first->vertex(k)))] = 1;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->is_in_domain()) out.triangles.push_back({index.at(f->vertex(0)), index.at(f->vertex(1)), index.at(f->vertex(2))});
  if (band.depths.empty()) {
    for (std::size_t i = offset; i < out.points_m.size(); ++i)
      if (on_ring[i]) {
        auto& p = out.points_m[i];
        const double rho = std::hypot(p[0] / b_m, p[1] / c_m);
        p = {p[0] / rho, p[1] / rho};
        out.on_rim[i] = 1;
        out.ring_rho[i] = 1;
      }
    return out;
  }
  // The band's innermost ring joined to CGAL's boundary, both in angle order.
  std::vector<std::pair<double, int>> inner;
  for (std::size_t i = offset; i < out.points_m.size(); ++i)
    if (on_ring[i]) inner.push_back({parametric_angle(b_m, c_m, out.points_m[i][0], out.points_m[i][1]), static_cast<int>(i)});
  std::sort(inner.begin(), inner.end());
  std::vector<int> inner_index;
  std::vector<double> inner_angle;
  for (const auto& [t, i] : inner) {
    inner_angle.push_back(t);
    inner_index.push_back(i);
  }
  stitch(ring.back(), rim_angle, inner_index, inner_angle, out.triangles);
  return out;
}

}  // namespace clatter::kernels::fem
