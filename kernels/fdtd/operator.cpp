#include "kernels/fdtd/operator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace clatter::kernels::fdtd {

const char* scheme_name(Scheme s) { return s == Scheme::srl ? "srl" : "me4"; }

std::optional<Scheme> scheme_from_name(std::string_view name) {
  if (name == "me4") return Scheme::me4;
  if (name == "srl") return Scheme::srl;
  return std::nullopt;
}

namespace {
// The me4 stencil's points besides the centre: axis neighbours at 1 and 2, and face diagonals.
std::vector<std::array<int, 3>> me4_offsets() {
  std::vector<std::array<int, 3>> o;
  for (int a = 0; a < 3; ++a)
    for (int d : {-2, -1, 1, 2}) {
      std::array<int, 3> v{};
      v[a] = d;
      o.push_back(v);
    }
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      for (int da : {-1, 1})
        for (int db : {-1, 1}) {
          std::array<int, 3> v{};
          v[a] = da;
          v[b] = db;
          o.push_back(v);
        }
  return o;
}
}  // namespace

Operator::Operator(const Problem& problem, const Box& owned)
    : problem_(problem), layout_(owned), pml_(problem, layout_) {
  for (int a = 0; a < 3; ++a)
    if (owned.hi[a] - owned.lo[a] < Layout::kHalo)
      throw std::invalid_argument("fdtd::Operator: a block needs at least " + std::to_string(Layout::kHalo) +
                                  " cells along every axis (the halo depth)");
  const double l2 = problem.courant() * problem.courant();
  lambda2_ = static_cast<float>(l2);
  c1_ = static_cast<float>(2.0 - 6.0 * l2);
  // lambda^2 L4: axis 1 -> 4/3, axis 2 -> -1/12, centre -15/2. (lambda^4/12) L2^2: axis 1 -> -12,
  // axis 2 -> 1, face diagonal -> 2, centre 42. Their sum over the 25 points is 2, as it must be.
  const double mu = l2 * l2 / 12.0;
  me4_.c0 = static_cast<float>(2.0 - 7.5 * l2 + 42.0 * mu);
  me4_.c1 = static_cast<float>(4.0 / 3.0 * l2 - 12.0 * mu);
  me4_.c2 = static_cast<float>(-l2 / 12.0 + mu);
  me4_.c3 = static_cast<float>(2.0 * mu);
  const Grid& g = problem.grid;
  const int blend = blend_cells(problem.scheme, g.pml);
  for (int a = 0; a < 3; ++a) {
    blend_[a].assign(static_cast<std::size_t>(g.n[a]), 0.0f);
    for (int i = 0; i < g.n[a] && blend > 0; ++i) {
      // Distance in cells from the layer's inner face, on the high side and (full mode) the low.
      double d = (g.n[a] - g.pml - 0.5) - i;
      if (!g.octant) d = std::min(d, i - (g.pml - 0.5));
      const double s = 1.0 - d / blend;  // 1 at the layer, 0 `blend` cells inside
      if (s > 0) blend_[a][static_cast<std::size_t>(i)] = static_cast<float>(std::min(1.0, s * s * (3.0 - 2.0 * s)));
    }
  }
  split_bulk(owned);
  build_cut_cells();
  build_point_source();
  counts_.owned = owned.cells();
  counts_.bulk = bulk_.cells();
  counts_.pml = pml_.cells();
  counts_.cut = static_cast<long long>(cut_.index.size()) - counts_.band;
  // Two pressure levels, the PML state, and per cut cell: index, gain, alpha, the six body columns,
  // the started column and p^{n-1}.
  counts_.bytes = 2 * layout_.size() * sizeof(float) + pml_.bytes() +
                  cut_.index.size() * (sizeof(long) + sizeof(float) * (1 + 6 + 6 + 1 + 1));
}

void Operator::split_bulk(const Box& owned) {
  bulk_ = problem_.grid.interior().intersect(owned);
  // Inner: bulk cells whose stencil reads no halo cell and no mirror ghost that is filled only
  // after the halo has arrived. The ghosts across a z mirror plane of the block's own rows are
  // filled before the interior (Engine::fill_z_mirror_ghosts), so inner reaches down to it:
  // otherwise the slab k < 2 would be a shell of rows two cells long (a quarter of the step's
  // time in an octant solve on one rank, measured).
  inner_ = bulk_;
  const bool z_mirror = problem_.grid.octant && owned.lo[2] == 0;
  for (int a = 0; a < 3; ++a) {
    if (!(a == 2 && z_mirror)) inner_.lo[a] = std::max(inner_.lo[a], owned.lo[a] + Layout::kHalo);
    inner_.hi[a] = std::min(inner_.hi[a], owned.hi[a] - Layout::kHalo);
  }
  // Shell: bulk minus inner, as up to six disjoint slabs (x slabs whole, y slabs within, z innermost).
  if (inner_.empty()) {
    if (!bulk_.empty()) shell_.push_back(bulk_);
    return;
  }
  Box rest = bulk_;
  for (int a = 0; a < 3; ++a) {
    Box low = rest, high = rest;
    low.hi[a] = inner_.lo[a];
    high.lo[a] = inner_.hi[a];
    if (!low.empty()) shell_.push_back(low);
    if (!high.empty()) shell_.push_back(high);
    rest.lo[a] = inner_.lo[a];
    rest.hi[a] = inner_.hi[a];
  }
}

void Operator::build_cut_cells() {
  if (problem_.field == 0) return;
  const Grid& g = problem_.grid;
  const SolidBody& solid_body = problem_.solid();
  const double dx = g.dx_m;
  const bool band = problem_.scheme == Scheme::me4;
  const int reach_band = band ? 2 : 0;
  // Cells whose class is needed: within one cell of the body's bounding box, and, for the band,
  // two more cells around those this block owns. Global indices, not clipped: a negative index in
  // octant mode is the mirror image of a solved cell, and cell_geometry mirrors it.
  Box region = bulk_;
  const std::array<double, 3> box_lo = solid_body.box_lo_m(), box_hi = solid_body.box_hi_m();
  for (int a = 0; a < 3; ++a) {
    // For the ellipsoid (box +-r) these are origin -+ (ceil(r / dx) + 1), as before meshes.
    const int below = static_cast<int>(std::floor(box_lo[a] / dx)) - 1;
    const int above = static_cast<int>(std::ceil(box_hi[a] / dx)) + 1;
    region.lo[a] = std::max(bulk_.lo[a] - reach_band, g.origin(a) + below);
    region.hi[a] = std::min(bulk_.hi[a] + reach_band, g.origin(a) + above);
  }
  if (region.empty()) return;
  enum : unsigned char { fluid, cut, solid };
  const std::array<int, 3> rn{region.hi[0] - region.lo[0], region.hi[1] - region.lo[1], region.hi[2] - region.lo[2]};
  auto slot = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(i - region.lo[0]) * rn[1] + (j - region.lo[1])) * rn[2] + (k - region.lo[2]);
  };
  auto geometry = [&](int i, int j, int k) {
    return cell_geometry(solid_body, {g.centre_m(0, i), g.centre_m(1, j), g.centre_m(2, k)}, dx, problem_.cut_cell_samples);
  };
  const Box owned_region = region.intersect(bulk_);
  std::vector<unsigned char> kind(static_cast<std::size_t>(region.cells()), fluid);
  // The geometry of this block's cut cells, kept in the order the loop below visits them (both
  // loops run i, j, k lexicographically): a mesh's cells cost hundreds of line casts each.
  std::vector<CellGeometry> owned_cut;
  for (int i = region.lo[0]; i < region.hi[0]; ++i)
    for (int j = region.lo[1]; j < region.hi[1]; ++j)
      for (int k = region.lo[2]; k < region.hi[2]; ++k) {
        const CellGeometry geo = geometry(i, j, k);
        const unsigned char c = geo.fully_fluid() ? fluid : geo.solid() ? solid : cut;
        kind[slot(i, j, k)] = c;
        if (c == cut && owned_region.contains({i, j, k})) owned_cut.push_back(geo);
      }
  auto near_body = [&](int i, int j, int k) {
    static const std::vector<std::array<int, 3>> offsets = me4_offsets();
    for (const auto& o : offsets) {
      const std::array<int, 3> c{i + o[0], j + o[1], k + o[2]};
      if (region.contains(c) && kind[slot(c[0], c[1], c[2])] != fluid) return true;
    }
    return false;
  };
  const double rho_c2_dt2 = problem_.rho_kg_m3 * problem_.c_m_s * problem_.c_m_s * problem_.dt_s * problem_.dt_s;
  std::size_t next_cut = 0;
  for (int i = owned_region.lo[0]; i < owned_region.hi[0]; ++i)
    for (int j = owned_region.lo[1]; j < owned_region.hi[1]; ++j)
      for (int k = owned_region.lo[2]; k < owned_region.hi[2]; ++k) {
        const std::size_t s = slot(i, j, k);
        if (kind[s] == solid) {
          ++counts_.solid;
          continue;
        }
        if (kind[s] == fluid) {
          if (!band || !near_body(i, j, k)) continue;
          // A band cell: the 7-point form with every face open is the standard leapfrog.
          ++counts_.band;
          cut_.index.push_back(layout_.at(i, j, k));
          cut_.gain.push_back(lambda2_);
          cut_.alpha.push_back({1, 1, 1, 1, 1, 1});
          cut_.body_all.push_back({});
          continue;
        }
        const CellGeometry& geo = owned_cut[next_cut++];
        double open = 0;
        for (double a : geo.alpha) open += a;
        // Stability: an effective volume of at least (sum of open faces)/6 keeps the standard CFL limit.
        const double beta_eff = std::max(geo.beta, open / 6.0);
        cut_.index.push_back(layout_.at(i, j, k));
        cut_.gain.push_back(static_cast<float>(lambda2_ / beta_eff));
        std::array<float, 6> alpha{};
        for (int f = 0; f < 6; ++f) alpha[f] = static_cast<float>(geo.alpha[f]);
        cut_.alpha.push_back(alpha);
        std::array<float, 6> body{};
        for (int f = 0; f < 6; ++f)
          body[static_cast<std::size_t>(f)] =
              static_cast<float>(-rho_c2_dt2 / (beta_eff * dx) * geo.body_flux[static_cast<std::size_t>(f)]);
        cut_.body_all.push_back(body);
      }
}

void Operator::build_point_source() {
  if (problem_.field != 0) return;
  // A monopole of volume acceleration psi at the origin (a cell corner), spread over the cells
  // around it with interpolation weights K per axis: linear (2 cells, error O((k dx)^2)) for srl,
  // cubic Lagrange (4 cells: -1/16, 9/16, 9/16, -1/16; error O((k dx)^4)) for me4.
  //   srl: p+ gets dt^2 f with f = K psi(t_n), second order like the scheme.
  //   me4: the scheme is the wave operator times (1 + (dt^2/12)(d_tt + c^2 Lap)) to fourth order,
  //        so the source must carry that factor too: dt^2 (K psi_smooth + (lambda^2/12) L7 K psi(t_n)),
  //        psi_smooth = psi + (dt^2/12) psi'' by the second difference. Without it the radiated
  //        amplitude is (omega dt)^2/6 too high (1 % at 4 kHz and dt = 1/96000 s).
  // In octant mode the cells on the negative side are mirror images of solved ones, with the same
  // weights, so only the solved ones are kept.
  const Grid& g = problem_.grid;
  const Problem& p = problem_;
  const double total = p.rho_kg_m3 * p.c_m_s * p.c_m_s * p.dt_s * p.dt_s / std::pow(g.dx_m, 3);
  const bool me4 = p.scheme == Scheme::me4;
  // Offsets -3..2 from the origin's cell hold the kernel and its 7-point Laplacian.
  constexpr int lo = -3, span = 6;
  auto w1 = [&](int o) {
    if (me4) return o == -2 || o == 1 ? -1.0 / 16 : o == -1 || o == 0 ? 9.0 / 16 : 0.0;
    return o == -1 || o == 0 ? 0.5 : 0.0;
  };
  auto kernel = [&](int ox, int oy, int oz) { return w1(ox) * w1(oy) * w1(oz); };
  for (int ox = lo; ox < lo + span; ++ox)
    for (int oy = lo; oy < lo + span; ++oy)
      for (int oz = lo; oz < lo + span; ++oz) {
        if (g.octant && (ox < 0 || oy < 0 || oz < 0)) continue;
        const double k = kernel(ox, oy, oz);
        double lap = 0;
        if (me4)
          lap = ((kernel(ox - 1, oy, oz) + kernel(ox + 1, oy, oz)) + (kernel(ox, oy - 1, oz) + kernel(ox, oy + 1, oz)) +
                 (kernel(ox, oy, oz - 1) + kernel(ox, oy, oz + 1))) - 6 * k;
        if (k == 0 && lap == 0) continue;
        const std::array<int, 3> c{g.origin(0) + ox, g.origin(1) + oy, g.origin(2) + oz};
        if (!layout_.owned.contains(c)) continue;
        SourceCell cell;
        cell.index = layout_.at(c);
        if (me4) {
          cell.smoothed = static_cast<float>(total * k);
          cell.now = static_cast<float>(total * (static_cast<double>(lambda2_) / 12.0) * lap);
        } else {
          cell.now = static_cast<float>(total * k);
        }
        point_source_.push_back(cell);
      }
}

}  // namespace clatter::kernels::fdtd
