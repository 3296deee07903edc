#include "kernels/fdtd/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace clatter::kernels::fdtd {

int field_parity(int field, int axis) {
  // Rows: fields 0..6; columns: mirror across x, y, z (eqs. 16-21 of Chadwick et al. 2012).
  static constexpr int parity[7][3] = {{+1, +1, +1}, {-1, +1, +1}, {+1, -1, +1}, {+1, +1, -1},
                                       {+1, -1, -1}, {-1, +1, -1}, {-1, -1, +1}};
  return parity[field][axis];
}

bool CellGeometry::fully_fluid() const {
  return beta == 1.0 && std::all_of(alpha.begin(), alpha.end(), [](double a) { return a == 1.0; });
}

bool CellGeometry::solid() const {
  double open = 0;
  for (double a : alpha) open += a;
  return beta <= 0.0 || open <= 0.0;
}

namespace {

// Solid part of the segment [lo, hi] along an axis where the body spans [-e, e], e^2 = e2.
struct Chord {
  double length = 0, moment = 0;  // length and first moment (integral of the coordinate)
};
Chord chord(double lo, double hi, double semi_axis, double q) {
  if (q <= 0) return {};
  const double e = semi_axis * std::sqrt(q);
  const double a = std::max(lo, -e), b = std::min(hi, e);
  if (b <= a) return {};
  return {b - a, 0.5 * (b * b - a * a)};
}

// Solid area and first moments of the face at `normal_axis` = `plane`, spanned by axes u (sampled)
// and v (analytic), within [lo, hi] of the cell.
struct FaceSolid {
  double area = 0;
  std::array<double, 3> moment{};  // integral of x, y, z over the solid part (normal entry unused)
};

FaceSolid face_solid(const Ellipsoid& e, int normal, double plane, const std::array<double, 3>& lo,
                     const std::array<double, 3>& hi, int m) {
  const std::array<double, 3> r{e.a_m, e.b_m, e.c_m};
  const int u = normal == 0 ? 1 : 0;   // sampled axis
  const int v = normal == 2 ? 1 : 2;   // analytic axis
  const double step = (hi[u] - lo[u]) / m;
  FaceSolid f;
  for (int s = 0; s < m; ++s) {
    const double cu = lo[u] + (s + 0.5) * step;
    const double q = 1.0 - plane * plane / (r[normal] * r[normal]) - cu * cu / (r[u] * r[u]);
    const Chord c = chord(lo[v], hi[v], r[v], q);
    f.area += c.length * step;
    f.moment[u] += cu * c.length * step;
    f.moment[v] += c.moment * step;
  }
  return f;
}

CellGeometry canonical_geometry(const Ellipsoid& e, const std::array<double, 3>& c, double dx, int m) {
  const std::array<double, 3> r{e.a_m, e.b_m, e.c_m};
  std::array<double, 3> lo{}, hi{};
  double f_min = 0, f_max = 0;  // range of x^2/A^2 + y^2/B^2 + z^2/C^2 over the cell (c >= 0)
  for (int a = 0; a < 3; ++a) {
    lo[a] = c[a] - 0.5 * dx;
    hi[a] = c[a] + 0.5 * dx;
    const double near = std::max(lo[a], 0.0);
    f_min += near * near / (r[a] * r[a]);
    f_max += hi[a] * hi[a] / (r[a] * r[a]);
  }
  CellGeometry g;
  if (f_min >= 1.0) {  // entirely outside the (convex) body
    g.alpha.fill(1.0);
    return g;
  }
  if (f_max <= 1.0) {  // entirely inside
    g.beta = 0;
    g.alpha.fill(0.0);
    return g;
  }
  // Volume: sample (x, y), exact chord along z.
  const double step = dx / m;
  double solid_volume = 0;
  for (int sx = 0; sx < m; ++sx)
    for (int sy = 0; sy < m; ++sy) {
      const double x = lo[0] + (sx + 0.5) * step, y = lo[1] + (sy + 0.5) * step;
      solid_volume += chord(lo[2], hi[2], r[2], 1.0 - x * x / (r[0] * r[0]) - y * y / (r[1] * r[1])).length;
    }
  g.beta = 1.0 - solid_volume * step * step / (dx * dx * dx);

  std::array<FaceSolid, 6> f;
  for (int a = 0; a < 3; ++a) {
    f[2 * a] = face_solid(e, a, lo[a], lo, hi, m);
    f[2 * a + 1] = face_solid(e, a, hi[a], lo, hi, m);
  }
  const double area = dx * dx;
  for (int i = 0; i < 6; ++i) g.alpha[i] = 1.0 - f[i].area / area;
  // Outward normals: -1 on low faces, +1 on high faces. g_i . n integrated over each solid part.
  auto d = [&](int axis, auto value) { return value(f[2 * axis + 1]) - value(f[2 * axis]); };
  auto area_of = [](const FaceSolid& s) { return s.area; };
  auto mx = [](const FaceSolid& s) { return s.moment[0]; };
  auto my = [](const FaceSolid& s) { return s.moment[1]; };
  auto mz = [](const FaceSolid& s) { return s.moment[2]; };
  g.body_flux[0] = d(0, area_of) / area;                  // translation x: g = e_x
  g.body_flux[1] = d(1, area_of) / area;                  // translation y
  g.body_flux[2] = d(2, area_of) / area;                  // translation z
  g.body_flux[3] = (-d(1, mz) + d(2, my)) / area;         // rotation about x: g = (0, -z, y)
  g.body_flux[4] = (d(0, mz) - d(2, mx)) / area;          // rotation about y: g = (z, 0, -x)
  g.body_flux[5] = (-d(0, my) + d(1, mx)) / area;         // rotation about z: g = (-y, x, 0)
  return g;
}

}  // namespace

CellGeometry cell_geometry(const Ellipsoid& body, const std::array<double, 3>& centre_m, double dx_m, int samples) {
  const std::array<double, 3> canonical{std::abs(centre_m[0]), std::abs(centre_m[1]), std::abs(centre_m[2])};
  CellGeometry g = canonical_geometry(body, canonical, dx_m, samples);
  for (int a = 0; a < 3; ++a) {
    if (centre_m[a] >= 0) continue;
    std::swap(g.alpha[2 * a], g.alpha[2 * a + 1]);
    for (int i = 0; i < 6; ++i) g.body_flux[i] *= field_parity(i + 1, a);
  }
  return g;
}

}  // namespace clatter::kernels::fdtd
