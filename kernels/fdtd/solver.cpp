#include "kernels/fdtd/solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "kernels/pulse.hpp"

namespace clatter::kernels::fdtd {

Solver::Solver(const Problem& problem, const Box& owned)
    : problem_(problem), layout_(owned), now_(layout_.size(), 0.0f), next_(layout_.size(), 0.0f) {
  const double l2 = problem.courant() * problem.courant();
  lambda2_ = static_cast<float>(l2);
  c1_ = static_cast<float>(2.0 - 6.0 * l2);
  bulk_ = problem.grid.interior().intersect(owned);
  // Inner: bulk cells none of whose neighbours is a halo cell.
  inner_ = bulk_;
  for (int a = 0; a < 3; ++a) {
    inner_.lo[a] = std::max(inner_.lo[a], owned.lo[a] + 1);
    inner_.hi[a] = std::min(inner_.hi[a], owned.hi[a] - 1);
  }
  // Shell: bulk minus inner, as up to six disjoint slabs (x slabs whole, y slabs within, z innermost).
  if (inner_.empty()) {
    if (!bulk_.empty()) shell_.push_back(bulk_);
  } else {
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
  pml_ = std::make_unique<Pml>(problem_, layout_);
  build_cut_cells();
  if (problem.field == 0) {
    // A monopole of volume acceleration psi at the origin, shared by the 8 cells around it
    // (in octant mode, cell (0,0,0) stands for all 8).
    const Grid& g = problem.grid;
    const double share = problem.rho_kg_m3 * problem.c_m_s * problem.c_m_s * problem.dt_s * problem.dt_s /
                         std::pow(g.dx_m, 3) / 8.0;
    for (int bx = 0; bx < 2; ++bx)
      for (int by = 0; by < 2; ++by)
        for (int bz = 0; bz < 2; ++bz) {
          std::array<int, 3> c{g.origin(0) - bx, g.origin(1) - by, g.origin(2) - bz};
          if (g.octant && (bx || by || bz)) continue;
          if (owned.contains(c)) point_source_.push_back({layout_.at(c), static_cast<float>(share)});
        }
  }
  counts_.owned = owned.cells();
  counts_.bulk = bulk_.cells();
  counts_.pml = pml_->cells();
  counts_.cut = static_cast<long long>(cut_.index.size());
  counts_.bytes = 2 * now_.size() * sizeof(float) + pml_->bytes() +
                  cut_.index.size() * (sizeof(long) + sizeof(float) * (1 + 6 + 6 + 1 + 1));
  start(problem.field);
}

void Solver::build_cut_cells() {
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
  cut_.old.resize(cut_.index.size());
}

void Solver::start(int field) {
  if ((field == 0) != (problem_.field == 0)) throw std::logic_error("Solver::start: monopole and body fields do not mix");
  problem_.field = field;
  std::fill(now_.begin(), now_.end(), 0.0f);
  std::fill(next_.begin(), next_.end(), 0.0f);
  pml_->reset();
  cut_.body.resize(cut_.body_all.size());
  for (std::size_t c = 0; c < cut_.body_all.size(); ++c) cut_.body[c] = field > 0 ? cut_.body_all[c][static_cast<std::size_t>(field - 1)] : 0.0f;
}

void Solver::fill_mirror_ghosts() {
  if (!problem_.grid.octant) return;
  const Box& o = layout_.owned;
  for (int a = 0; a < 3; ++a) {
    if (o.lo[a] != 0) continue;
    const float sign = static_cast<float>(problem_.parity(a));
    Box plane = o;
    plane.hi[a] = 1;
    const long s = layout_.stride[a];
    for (int i = plane.lo[0]; i < plane.hi[0]; ++i)
      for (int j = plane.lo[1]; j < plane.hi[1]; ++j)
        for (int k = plane.lo[2]; k < plane.hi[2]; ++k) {
          const long here = layout_.at(i, j, k);
          now_[static_cast<std::size_t>(here - s)] = sign * now_[static_cast<std::size_t>(here)];
        }
  }
}

void Solver::begin_step() {
  fill_mirror_ghosts();
  for (std::size_t c = 0; c < cut_.index.size(); ++c) cut_.old[c] = next_[static_cast<std::size_t>(cut_.index[c])];
}

void Solver::update_bulk(const Box& box) {
  if (box.empty()) return;
  const long sx = layout_.stride[0], sy = layout_.stride[1];
  const float c1 = c1_, l2 = lambda2_;
  const int nk = box.hi[2] - box.lo[2];
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j) {
      const long row = layout_.at(i, j, box.lo[2]);
      const float* __restrict p = now_.data() + row;
      const float* __restrict xm = p - sx;
      const float* __restrict xp = p + sx;
      const float* __restrict ym = p - sy;
      const float* __restrict yp = p + sy;
      float* __restrict q = next_.data() + row;
      // Neighbours summed in mirror-symmetric pairs, so mirrored cells round identically.
      for (int k = 0; k < nk; ++k)
        q[k] = (c1 * p[k] - q[k]) + l2 * (((xm[k] + xp[k]) + (ym[k] + yp[k])) + (p[k - 1] + p[k + 1]));
    }
}

void Solver::update_cut_cells(float psi) {
  const long sx = layout_.stride[0], sy = layout_.stride[1];
  const float* p = now_.data();
  for (std::size_t c = 0; c < cut_.index.size(); ++c) {
    const long i = cut_.index[c];
    const auto& a = cut_.alpha[c];
    const float pc = p[i];
    const float s = ((a[0] * (p[i - sx] - pc) + a[1] * (p[i + sx] - pc)) + (a[2] * (p[i - sy] - pc) + a[3] * (p[i + sy] - pc))) +
                    (a[4] * (p[i - 1] - pc) + a[5] * (p[i + 1] - pc));
    next_[static_cast<std::size_t>(i)] = (2.0f * pc - cut_.old[c]) + cut_.gain[c] * s + cut_.body[c] * psi;
  }
}

void Solver::finish_step(double t_s) {
  pml_->update(now_.data(), next_.data());
  const float psi = static_cast<float>(pulse(t_s, problem_.h_s));
  update_cut_cells(psi);
  for (const auto& [cell, share] : point_source_) next_[static_cast<std::size_t>(cell)] += share * psi;
  now_.swap(next_);
}

}  // namespace clatter::kernels::fdtd
