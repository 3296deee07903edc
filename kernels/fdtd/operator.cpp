#include "kernels/fdtd/operator.hpp"

#include <algorithm>
#include <cmath>

namespace clatter::kernels::fdtd {

Operator::Operator(const Problem& problem, const Box& owned)
    : problem_(problem), layout_(owned), pml_(problem, layout_) {
  const double l2 = problem.courant() * problem.courant();
  lambda2_ = static_cast<float>(l2);
  c1_ = static_cast<float>(2.0 - 6.0 * l2);
  split_bulk(owned);
  build_cut_cells();
  build_point_source();
  counts_.owned = owned.cells();
  counts_.bulk = bulk_.cells();
  counts_.pml = pml_.cells();
  counts_.cut = static_cast<long long>(cut_.index.size());
  // Two pressure levels, the PML state, and per cut cell: index, gain, alpha, the six body columns,
  // the started column and p^{n-1}.
  counts_.bytes = 2 * layout_.size() * sizeof(float) + pml_.bytes() +
                  cut_.index.size() * (sizeof(long) + sizeof(float) * (1 + 6 + 6 + 1 + 1));
}

void Operator::split_bulk(const Box& owned) {
  bulk_ = problem_.grid.interior().intersect(owned);
  // Inner: bulk cells none of whose neighbours is a halo cell.
  inner_ = bulk_;
  for (int a = 0; a < 3; ++a) {
    inner_.lo[a] = std::max(inner_.lo[a], owned.lo[a] + 1);
    inner_.hi[a] = std::min(inner_.hi[a], owned.hi[a] - 1);
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
  const Ellipsoid& e = problem_.body;
  const double dx = g.dx_m;
  // Only cells whose centre lies within one cell of the ellipsoid's bounding box can be cut.
  Box candidates = bulk_;
  const std::array<double, 3> r{e.a_m, e.b_m, e.c_m};
  for (int a = 0; a < 3; ++a) {
    const int reach = static_cast<int>(std::ceil(r[a] / dx)) + 1;
    candidates.lo[a] = std::max(candidates.lo[a], g.origin(a) - reach);
    candidates.hi[a] = std::min(candidates.hi[a], g.origin(a) + reach);
  }
  const double rho_c2_dt2 = problem_.rho_kg_m3 * problem_.c_m_s * problem_.c_m_s * problem_.dt_s * problem_.dt_s;
  for (int i = candidates.lo[0]; i < candidates.hi[0]; ++i)
    for (int j = candidates.lo[1]; j < candidates.hi[1]; ++j)
      for (int k = candidates.lo[2]; k < candidates.hi[2]; ++k) {
        const CellGeometry geo =
            cell_geometry(e, {g.centre_m(0, i), g.centre_m(1, j), g.centre_m(2, k)}, dx, problem_.cut_cell_samples);
        if (geo.fully_fluid()) continue;
        if (geo.solid()) {
          ++counts_.solid;
          continue;
        }
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
  // A monopole of volume acceleration psi at the origin, shared by the 8 cells around it (in
  // octant mode, cell (0,0,0) stands for all 8).
  const Grid& g = problem_.grid;
  const Problem& p = problem_;
  const double share = p.rho_kg_m3 * p.c_m_s * p.c_m_s * p.dt_s * p.dt_s / std::pow(g.dx_m, 3) / 8.0;
  for (int bx = 0; bx < 2; ++bx)
    for (int by = 0; by < 2; ++by)
      for (int bz = 0; bz < 2; ++bz) {
        std::array<int, 3> c{g.origin(0) - bx, g.origin(1) - by, g.origin(2) - bz};
        if (g.octant && (bx || by || bz)) continue;
        if (layout_.owned.contains(c)) point_source_.push_back({layout_.at(c), static_cast<float>(share)});
      }
}

}  // namespace clatter::kernels::fdtd
