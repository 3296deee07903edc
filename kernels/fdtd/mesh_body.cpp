#include "kernels/fdtd/mesh_body.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "kernels/mass_properties.hpp"

namespace clatter::kernels::fdtd {

namespace {

// The two axes across `along`, ascending.
std::array<int, 2> across(int along) { return along == 0 ? std::array<int, 2>{1, 2} : along == 1 ? std::array<int, 2>{0, 2} : std::array<int, 2>{0, 1}; }

// (u, v, along) is a right-handed frame for along = 0 (y, z, x) and 2 (x, y, z), left-handed for 1
// (x, z, y): a triangle counter-clockwise in (u, v) has its normal along +along times this.
int handedness(int along) { return along == 1 ? -1 : 1; }

thread_local std::vector<std::array<double, 2>> t_intervals;

}  // namespace

int MeshBody::Bins::bin_u(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - lo_u) / width_u)), 0, nu - 1);
}
int MeshBody::Bins::bin_v(double x) const {
  return std::clamp(static_cast<int>(std::floor((x - lo_v) / width_v)), 0, nv - 1);
}

MeshBody::MeshBody(std::vector<std::array<double, 3>> vertices_m, std::vector<std::array<int, 3>> triangles)
    : vertices_(std::move(vertices_m)), triangles_(std::move(triangles)) {
  if (vertices_.empty() || triangles_.empty()) throw std::invalid_argument("mesh body: the mesh has no triangles");
  const MeshMassProperties mass = mesh_mass_properties(vertices_, triangles_);
  double extent = 0;
  for (const auto& v : vertices_)
    for (int a = 0; a < 3; ++a) extent = std::max(extent, std::abs(v[a] - mass.centroid_m[a]));
  if (!(std::abs(mass.volume_m3) > 1e-12 * extent * extent * extent))
    throw std::invalid_argument("mesh body: the mesh encloses no volume");
  if (mass.volume_m3 < 0)
    for (auto& t : triangles_) std::swap(t[1], t[2]);
  volume_ = std::abs(mass.volume_m3);
  offset_ = mass.centroid_m;
  box_lo_ = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  box_hi_ = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (auto& v : vertices_) {
    double r2 = 0;
    for (int a = 0; a < 3; ++a) {
      v[a] -= offset_[a];
      box_lo_[a] = std::min(box_lo_[a], v[a]);
      box_hi_[a] = std::max(box_hi_[a], v[a]);
      r2 += v[a] * v[a];
    }
    radius_ = std::max(radius_, std::sqrt(r2));
  }
  triangle_box_.reserve(triangles_.size());
  for (const auto& t : triangles_) {
    std::array<double, 6> b{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        b[a] = std::min(b[a], vertices_[t[k]][a]);
        b[3 + a] = std::max(b[3 + a], vertices_[t[k]][a]);
      }
    triangle_box_.push_back(b);
  }
  for (int a = 0; a < 3; ++a) build_bins(a);
  const auto mismatch = check_mirror_symmetry();
  for (int a = 0; a < 3; ++a)
    if (mismatch[a] <= kMirrorTolerance) mirror_axes_ |= 1 << a;
  mismatch_ = std::max({mismatch[0], mismatch[1], mismatch[2]});
}

void MeshBody::build_bins(int along) {
  Bins& b = bins_[along];
  const auto uv = across(along);
  b.u = uv[0];
  b.v = uv[1];
  const double eu = box_hi_[b.u] - box_lo_[b.u], ev = box_hi_[b.v] - box_lo_[b.v];
  // About as many bins as triangles, square-ish: a line then tests a handful of triangles.
  const double n = static_cast<double>(triangles_.size());
  const double aspect = eu > 0 && ev > 0 ? eu / ev : 1.0;
  b.nu = std::clamp(static_cast<int>(std::ceil(std::sqrt(n * aspect))), 1, 4096);
  b.nv = std::clamp(static_cast<int>(std::ceil(n / b.nu)), 1, 4096);
  b.lo_u = box_lo_[b.u];
  b.lo_v = box_lo_[b.v];
  b.width_u = eu > 0 ? eu / b.nu : 1.0;
  b.width_v = ev > 0 ? ev / b.nv : 1.0;
  // Inclusive ranges: floor((x - lo) / w) is monotone in x, so a line at x in [min, max] of a
  // triangle's projection always looks in a bin that lists the triangle.
  std::vector<int> count(static_cast<std::size_t>(b.nu) * b.nv + 1, 0);
  auto each_bin = [&](std::size_t t, auto visit) {
    const auto& box = triangle_box_[t];
    for (int i = b.bin_u(box[b.u]); i <= b.bin_u(box[3 + b.u]); ++i)
      for (int j = b.bin_v(box[b.v]); j <= b.bin_v(box[3 + b.v]); ++j) visit(static_cast<std::size_t>(i) * b.nv + j);
  };
  for (std::size_t t = 0; t < triangles_.size(); ++t) each_bin(t, [&](std::size_t s) { ++count[s + 1]; });
  for (std::size_t s = 1; s < count.size(); ++s) count[s] += count[s - 1];
  b.start = count;
  b.triangle.resize(static_cast<std::size_t>(count.back()));
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    each_bin(t, [&](std::size_t s) { b.triangle[static_cast<std::size_t>(count[s]++)] = static_cast<int>(t); });
}

void MeshBody::crossings(int along, double pu, double pv, std::vector<Crossing>& out) const {
  out.clear();
  const Bins& b = bins_[along];
  if (pu < box_lo_[b.u] || pu > box_hi_[b.u] || pv < box_lo_[b.v] || pv > box_hi_[b.v]) return;
  const std::size_t s = static_cast<std::size_t>(b.bin_u(pu)) * b.nv + b.bin_v(pv);
  const int u = b.u, v = b.v;
  // Side of P = (pu, pv) (perturbed by (eps, eps^2)) of the edge i -> j, > 0 on its left. Evaluated
  // with the lower vertex index first so both triangles of the edge get the same number, negated.
  auto side = [&](int i, int j, double& value) {
    const bool swapped = i > j;
    if (swapped) std::swap(i, j);
    const auto& a = vertices_[static_cast<std::size_t>(i)];
    const auto& c = vertices_[static_cast<std::size_t>(j)];
    const double du = c[u] - a[u], dv = c[v] - a[v];
    value = du * (pv - a[v]) - dv * (pu - a[u]);
    // d value = du eps^2 - dv eps for the perturbed point.
    int sign = value > 0 ? 1 : value < 0 ? -1 : dv != 0 ? (dv < 0 ? 1 : -1) : du > 0 ? 1 : du < 0 ? -1 : 0;
    if (swapped) {
      value = -value;
      sign = -sign;
    }
    return sign;
  };
  for (int k = b.start[s]; k < b.start[s + 1]; ++k) {
    const int t = b.triangle[static_cast<std::size_t>(k)];
    const auto& box = triangle_box_[static_cast<std::size_t>(t)];
    if (pu < box[u] || pu > box[3 + u] || pv < box[v] || pv > box[3 + v]) continue;
    const auto& tri = triangles_[static_cast<std::size_t>(t)];
    double w0, w1, w2;  // barycentric weights (unnormalized) of the corners
    const int s0 = side(tri[1], tri[2], w0);
    if (s0 == 0) continue;
    const int s1 = side(tri[2], tri[0], w1);
    if (s1 != s0) continue;
    const int s2 = side(tri[0], tri[1], w2);
    if (s2 != s0) continue;
    const auto& a = vertices_[static_cast<std::size_t>(tri[0])];
    const auto& c = vertices_[static_cast<std::size_t>(tri[1])];
    const auto& d = vertices_[static_cast<std::size_t>(tri[2])];
    const double sum = w0 + w1 + w2;
    double at = sum != 0 ? (w0 * a[along] + w1 * c[along] + w2 * d[along]) / sum : (a[along] + c[along] + d[along]) / 3;
    at = std::clamp(at, box[along], box[3 + along]);
    // Normal along +along: the line leaves the solid here.
    out.push_back({at, s0 * handedness(along) > 0 ? -1 : 1});
  }
  std::sort(out.begin(), out.end(), [](const Crossing& x, const Crossing& y) { return x.t < y.t || (x.t == y.t && x.enter > y.enter); });
}

void MeshBody::solid_intervals(int along, int axis_p, double p, int axis_q, double q,
                               std::vector<std::array<double, 2>>& out) const {
  thread_local std::vector<Crossing> found;
  const auto uv = across(along);
  const double pu = axis_p == uv[0] ? p : q, pv = axis_p == uv[0] ? q : p;
  (void)axis_q;
  crossings(along, pu, pv, found);
  out.clear();
  int winding = 0;
  double begin = 0;
  for (const Crossing& c : found) {
    const int before = winding;
    winding += c.enter;
    if (before <= 0 && winding > 0) begin = c.t;
    if (before > 0 && winding <= 0 && c.t > begin) out.push_back({begin, c.t});
  }
}

std::vector<std::array<double, 2>> MeshBody::intervals(int along, int axis_p, double p, int axis_q, double q) const {
  std::vector<std::array<double, 2>> out;
  solid_intervals(along, axis_p, p, axis_q, q, out);
  return out;
}

Chord MeshBody::chord(int along, int axis_p, double p, int axis_q, double q, double lo, double hi) const {
  if (hi < box_lo_[along] || lo > box_hi_[along]) return {};
  solid_intervals(along, axis_p, p, axis_q, q, t_intervals);
  Chord c;
  for (const auto& s : t_intervals) {
    const double a = std::max(lo, s[0]), b = std::min(hi, s[1]);
    if (b <= a) continue;
    c.length += b - a;
    c.moment += 0.5 * (b * b - a * a);
  }
  return c;
}

bool MeshBody::contains(double x, double y, double z) const {
  solid_intervals(2, 0, x, 1, y, t_intervals);
  for (const auto& s : t_intervals)
    if (s[0] < z && z < s[1]) return true;
  return false;
}

BoxClass MeshBody::classify(const std::array<double, 3>& lo, const std::array<double, 3>& hi) const {
  for (int a = 0; a < 3; ++a)
    if (hi[a] < box_lo_[a] || lo[a] > box_hi_[a]) return BoxClass::outside;
  // No triangle's box meets the cell's: no surface in the cell, which is then all one side.
  const Bins& b = bins_[2];
  for (int i = b.bin_u(lo[0]); i <= b.bin_u(hi[0]); ++i)
    for (int j = b.bin_v(lo[1]); j <= b.bin_v(hi[1]); ++j) {
      const std::size_t s = static_cast<std::size_t>(i) * b.nv + j;
      for (int k = b.start[s]; k < b.start[s + 1]; ++k) {
        const auto& box = triangle_box_[static_cast<std::size_t>(b.triangle[static_cast<std::size_t>(k)])];
        if (box[0] <= hi[0] && box[3] >= lo[0] && box[1] <= hi[1] && box[4] >= lo[1] && box[2] <= hi[2] && box[5] >= lo[2])
          return BoxClass::maybe_cut;
      }
    }
  return contains(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])) ? BoxClass::inside
                                                                                          : BoxClass::outside;
}

std::array<double, 3> MeshBody::check_mirror_symmetry() const {
  // Sampled lines along each axis, over the box at offsets that avoid the mirror planes and the
  // diagonals (13 x 11 positions), compared with their images in the three planes. A symmetric
  // mesh gives the same intervals up to rounding; the tolerance scale is the bounding radius.
  // worst[a]: the mismatch under x_a -> -x_a.
  std::array<double, 3> worst{};
  constexpr int np = 13, nq = 11;
  const double tol_abs = kMirrorTolerance * radius_;
  auto clean = [&](std::vector<std::array<double, 2>> s) {
    s.erase(std::remove_if(s.begin(), s.end(), [&](const auto& i) { return i[1] - i[0] <= tol_abs; }), s.end());
    return s;
  };
  auto compare = [&](const std::vector<std::array<double, 2>>& x, const std::vector<std::array<double, 2>>& y) {
    if (x.size() != y.size()) return HUGE_VAL;
    double d = 0;
    for (std::size_t i = 0; i < x.size(); ++i) d = std::max({d, std::abs(x[i][0] - y[i][0]), std::abs(x[i][1] - y[i][1])});
    return d / radius_;
  };
  for (int along = 0; along < 3; ++along) {
    const auto uv = across(along);
    for (int i = 0; i < np; ++i)
      for (int j = 0; j < nq; ++j) {
        const double pu = box_lo_[uv[0]] + (i + 0.37) / np * (box_hi_[uv[0]] - box_lo_[uv[0]]);
        const double pv = box_lo_[uv[1]] + (j + 0.61) / nq * (box_hi_[uv[1]] - box_lo_[uv[1]]);
        const auto here = clean(intervals(along, uv[0], pu, uv[1], pv));
        auto flipped = here;  // mirror across the plane normal to `along`
        std::reverse(flipped.begin(), flipped.end());
        for (auto& s : flipped) s = {-s[1], -s[0]};
        worst[along] = std::max(worst[along], compare(flipped, here));
        worst[uv[0]] = std::max(worst[uv[0]], compare(clean(intervals(along, uv[0], -pu, uv[1], pv)), here));
        worst[uv[1]] = std::max(worst[uv[1]], compare(clean(intervals(along, uv[0], pu, uv[1], -pv)), here));
      }
  }
  return worst;
}

}  // namespace clatter::kernels::fdtd
