#include "kernels/fdtd/engine.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/stage_log.hpp"
#include "kernels/pulse.hpp"

namespace clatter::kernels::fdtd {

Engine::Engine(const Operator& op, HaloExchange& halo)
    : op_(op),
      halo_(halo),
      now_(op.layout().size(), 0.0f),
      next_(op.layout().size(), 0.0f),
      pml_(op.pml().make_state()),
      cut_body_(op.cut_cells().index.size()),
      cut_old_(op.cut_cells().index.size()) {
  start(op.problem().field);
}

void Engine::start(int field) {
  if ((field == 0) != (op_.problem().field == 0))
    throw std::logic_error("Engine::start: monopole and body fields do not mix");
  field_ = field;
  std::fill(now_.begin(), now_.end(), 0.0f);
  std::fill(next_.begin(), next_.end(), 0.0f);
  op_.pml().reset(pml_);
  const auto& body_all = op_.cut_cells().body_all;
  for (std::size_t c = 0; c < body_all.size(); ++c)
    cut_body_[c] = field > 0 ? body_all[c][static_cast<std::size_t>(field - 1)] : 0.0f;
}

void Engine::step(double t_s) {
  halo_.start(now_.data());
  fill_mirror_ghosts();
  keep_cut_cell_old();
  {
    Stage s("interior");
    update_bulk(op_.inner_box());
  }
  {
    Stage s("halo wait");
    halo_.finish();
  }
  {
    Stage s("shell, PML, body");
    for (const auto& b : op_.shell_boxes()) update_bulk(b);
    op_.pml().update(pml_, now_.data(), next_.data());
    const float psi = static_cast<float>(pulse(t_s, op_.problem().h_s));
    update_cut_cells(psi);
    add_point_source(psi);
  }
  now_.swap(next_);
}

void Engine::fill_mirror_ghosts() {
  if (!op_.problem().grid.octant) return;
  const Layout& layout = op_.layout();
  const Box& o = layout.owned;
  for (int a = 0; a < 3; ++a) {
    if (o.lo[a] != 0) continue;
    const float sign = static_cast<float>(field_parity(field_, a));
    Box plane = o;
    plane.hi[a] = 1;
    const long s = layout.stride[a];
    for (int i = plane.lo[0]; i < plane.hi[0]; ++i)
      for (int j = plane.lo[1]; j < plane.hi[1]; ++j)
        for (int k = plane.lo[2]; k < plane.hi[2]; ++k) {
          const long here = layout.at(i, j, k);
          now_[static_cast<std::size_t>(here - s)] = sign * now_[static_cast<std::size_t>(here)];
        }
  }
}

void Engine::keep_cut_cell_old() {
  const auto& index = op_.cut_cells().index;
  for (std::size_t c = 0; c < index.size(); ++c) cut_old_[c] = next_[static_cast<std::size_t>(index[c])];
}

void Engine::update_bulk(const Box& box) {
  if (box.empty()) return;
  const Layout& layout = op_.layout();
  const long sx = layout.stride[0], sy = layout.stride[1];
  const float c1 = op_.c1(), l2 = op_.lambda2();
  const int nk = box.hi[2] - box.lo[2];
  for (int i = box.lo[0]; i < box.hi[0]; ++i)
    for (int j = box.lo[1]; j < box.hi[1]; ++j) {
      const long row = layout.at(i, j, box.lo[2]);
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

void Engine::update_cut_cells(float psi) {
  const CutCells& cut = op_.cut_cells();
  const long sx = op_.layout().stride[0], sy = op_.layout().stride[1];
  const float* p = now_.data();
  for (std::size_t c = 0; c < cut.index.size(); ++c) {
    const long i = cut.index[c];
    const auto& a = cut.alpha[c];
    const float pc = p[i];
    const float s = ((a[0] * (p[i - sx] - pc) + a[1] * (p[i + sx] - pc)) + (a[2] * (p[i - sy] - pc) + a[3] * (p[i + sy] - pc))) +
                    (a[4] * (p[i - 1] - pc) + a[5] * (p[i + 1] - pc));
    next_[static_cast<std::size_t>(i)] = (2.0f * pc - cut_old_[c]) + cut.gain[c] * s + cut_body_[c] * psi;
  }
}

void Engine::add_point_source(float psi) {
  for (const auto& [cell, share] : op_.point_source()) next_[static_cast<std::size_t>(cell)] += share * psi;
}

}  // namespace clatter::kernels::fdtd
