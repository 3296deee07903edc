#include "kernels/fdtd/pml.hpp"

#include <cmath>

namespace clatter::kernels::fdtd {

namespace {
// Depth (in cells) of a position, in cell units from the grid's low edge, into the absorbing layer.
double depth(const Grid& g, int axis, double position) {
  const double n = g.n[axis], l = g.pml;
  double d = position - (n - l);            // high layer
  if (!g.octant) d = std::max(d, l - position);  // low layer
  return std::max(d, 0.0);
}
}  // namespace

Pml::Pml(const Problem& problem, const Layout& layout)
    : layout_(layout), grid_(problem.grid), lambda2_(static_cast<float>(problem.courant() * problem.courant())) {
  const Grid& g = grid_;
  const double dt = problem.dt_s, dx = g.dx_m, rho = problem.rho_kg_m3, c = problem.c_m_s;
  const double l = g.pml;
  const double sigma_max = l > 0 ? -4.0 * c * std::log(problem.pml_reflection) / (2.0 * l * dx) : 0.0;
  auto sigma = [&](double d) { return l > 0 ? sigma_max * std::pow(d / l, 3) : 0.0; };
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i < g.n[a]; ++i) {
      const double s = sigma(depth(g, a, i + 0.5)), den = 1.0 + 0.5 * s * dt;
      cell_decay_[a].push_back(static_cast<float>((1.0 - 0.5 * s * dt) / den));
      cell_gain_[a].push_back(static_cast<float>(rho * c * c * dt / dx / den));
    }
    for (int f = 0; f <= g.n[a]; ++f) {
      const double s = sigma(depth(g, a, f)), den = 1.0 + 0.5 * s * dt;
      face_decay_[a].push_back(static_cast<float>((1.0 - 0.5 * s * dt) / den));
      face_gain_[a].push_back(static_cast<float>(dt / (rho * dx) / den));
    }
  }
  if (g.pml == 0) return;
  // Split each axis into layer and middle segments; every combination but all-middle is a region.
  std::array<std::vector<std::pair<Box, bool>>, 3> segments;
  for (int a = 0; a < 3; ++a) {
    auto seg = [&](int lo, int hi, bool damped) {
      Box b = g.all();
      b.lo[a] = lo;
      b.hi[a] = hi;
      segments[a].push_back({b, damped});
    };
    if (!g.octant) seg(0, g.pml, true);
    seg(g.octant ? 0 : g.pml, g.n[a] - g.pml, false);
    seg(g.n[a] - g.pml, g.n[a], true);
  }
  for (const auto& [bx, dx_damped] : segments[0])
    for (const auto& [by, dy_damped] : segments[1])
      for (const auto& [bz, dz_damped] : segments[2]) {
        const int damped = (dx_damped ? 1 : 0) | (dy_damped ? 2 : 0) | (dz_damped ? 4 : 0);
        if (damped == 0) continue;
        Region r;
        r.box = bx.intersect(by).intersect(bz).intersect(layout.owned);
        if (r.box.empty()) continue;
        r.damped = damped;
        const auto n = std::array<int, 3>{r.box.hi[0] - r.box.lo[0], r.box.hi[1] - r.box.lo[1], r.box.hi[2] - r.box.lo[2]};
        for (int a = 0; a < 3; ++a) {
          if (!(damped & (1 << a))) continue;
          auto fn = n;
          fn[a] += 1;
          r.face_stride[a] = {long(fn[1]) * fn[2], fn[2], 1};
          r.v[a].assign(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2], 0.0f);
          r.split_now[a].assign(static_cast<std::size_t>(n[0]) * n[1] * n[2], 0.0f);
          r.split_old[a].assign(r.split_now[a].size(), 0.0f);
        }
        regions_.push_back(std::move(r));
      }
}

long long Pml::cells() const {
  long long n = 0;
  for (const auto& r : regions_) n += r.box.cells();
  return n;
}

std::size_t Pml::bytes() const {
  std::size_t b = 0;
  for (const auto& r : regions_)
    for (int a = 0; a < 3; ++a) b += (r.v[a].size() + r.split_now[a].size() + r.split_old[a].size()) * sizeof(float);
  return b;
}

void Pml::update(const float* p_now, float* p_next) {
  for (auto& r : regions_) update_region(r, p_now, p_next);
}

void Pml::update_region(Region& r, const float* p_now, float* p_next) {
  const Box& b = r.box;
  const auto& st = layout_.stride;
  // 1. Face velocities of the damped axes, from the pressure gradient at t_n. The faces on the
  //    grid's outer boundary stay 0 (a rigid wall behind the layer).
  for (int a = 0; a < 3; ++a) {
    if (!(r.damped & (1 << a))) continue;
    Box faces = b;
    faces.hi[a] += 1;
    const auto& fs = r.face_stride[a];
    const float* fd = face_decay_[a].data();
    const float* fg = face_gain_[a].data();
    for (int i = faces.lo[0]; i < faces.hi[0]; ++i)
      for (int j = faces.lo[1]; j < faces.hi[1]; ++j)
        for (int k = faces.lo[2]; k < faces.hi[2]; ++k) {
          const std::array<int, 3> cell{i, j, k};
          const int g = cell[a];  // face between cells g-1 and g along a
          if (g == 0 || g == grid_.n[a]) continue;
          const long here = layout_.at(i, j, k);
          float& v = r.v[a][static_cast<std::size_t>((i - b.lo[0]) * fs[0] + (j - b.lo[1]) * fs[1] + (k - b.lo[2]))];
          v = fd[g] * v - fg[g] * (p_now[here] - p_now[here - st[a]]);
        }
  }
  // 2. Pressure: damped split parts explicitly, undamped parts through the leapfrog Laplacian.
  const long nyz = long(b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2]), nz = b.hi[2] - b.lo[2];
  for (int i = b.lo[0]; i < b.hi[0]; ++i)
    for (int j = b.lo[1]; j < b.hi[1]; ++j)
      for (int k = b.lo[2]; k < b.hi[2]; ++k) {
        const std::array<int, 3> cell{i, j, k};
        const long here = layout_.at(i, j, k);
        const long local = (i - b.lo[0]) * nyz + (j - b.lo[1]) * nz + (k - b.lo[2]);
        const float p = p_now[here];
        float split = 0.0f, pairs = 0.0f;
        int undamped = 0;
        for (int a = 0; a < 3; ++a) {
          if (r.damped & (1 << a)) {
            const auto& fs = r.face_stride[a];
            const long f = (i - b.lo[0]) * fs[0] + (j - b.lo[1]) * fs[1] + (k - b.lo[2]);
            const float dv = r.v[a][static_cast<std::size_t>(f + fs[a])] - r.v[a][static_cast<std::size_t>(f)];
            const float now = r.split_now[a][static_cast<std::size_t>(local)];
            float& old = r.split_old[a][static_cast<std::size_t>(local)];
            const float next = cell_decay_[a][static_cast<std::size_t>(cell[a])] * now -
                               cell_gain_[a][static_cast<std::size_t>(cell[a])] * dv;
            split += (next - 2.0f * now) + old;
            old = next;  // becomes split_now after the swap below
          } else {
            pairs += p_now[here - layout_.stride[a]] + p_now[here + layout_.stride[a]];
            ++undamped;
          }
        }
        p_next[here] = (2.0f * p - p_next[here]) + lambda2_ * (pairs - 2.0f * static_cast<float>(undamped) * p) + split;
      }
  for (int a = 0; a < 3; ++a) r.split_now[a].swap(r.split_old[a]);
}

}  // namespace clatter::kernels::fdtd
