#include "kernels/fdtd/recorder.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/stage_log.hpp"

namespace clatter::kernels::fdtd {

Recorder::Recorder(const Problem& problem, const std::vector<std::array<double, 3>>& listeners_m,
                   const Layout& layout, int n_samples)
    : n_samples_(static_cast<std::size_t>(n_samples)) {
  for (int l = 0; l < static_cast<int>(listeners_m.size()); ++l) {
    stencils_.push_back(listener_stencil(problem, listeners_m[static_cast<std::size_t>(l)]));
    for (int c = 0; c < Stencil::kCorners; ++c) {
      const auto& cell = stencils_.back().cell[static_cast<std::size_t>(c)];
      if (layout.owned.contains(cell)) probes_.push_back({l, c, layout.at(cell)});
    }
  }
  recorded_.resize(probes_.size() * n_samples_);
}

void Recorder::record(int n, const float* pressure) {
  Stage s("record");
  for (std::size_t q = 0; q < probes_.size(); ++q)
    recorded_[q * n_samples_ + static_cast<std::size_t>(n)] = pressure[static_cast<std::size_t>(probes_[q].index)];
}

bool Recorder::finite_at(int n) const {
  bool finite = true;
  for (std::size_t q = static_cast<std::size_t>(n); q < recorded_.size(); q += n_samples_)
    if (!std::isfinite(recorded_[q])) finite = false;
  return finite;
}

std::string Recorder::pack() const {
  std::string out;
  for (std::size_t q = 0; q < probes_.size(); ++q) {
    const int header[2] = {probes_[q].listener, probes_[q].corner};
    out.append(reinterpret_cast<const char*>(header), sizeof header);
    out.append(reinterpret_cast<const char*>(&recorded_[q * n_samples_]), sizeof(float) * n_samples_);
  }
  return out;
}

std::vector<float> interpolate_listeners(const std::vector<Stencil>& stencils, int n_samples,
                                         const std::vector<std::string>& packs) {
  const std::size_t ns = static_cast<std::size_t>(n_samples), record = 2 * sizeof(int) + ns * sizeof(float);
  std::vector<std::array<std::vector<float>, Stencil::kCorners>> corners(stencils.size());
  for (const auto& text : packs)
    for (std::size_t off = 0; off + record <= text.size(); off += record) {
      int header[2];
      std::memcpy(header, text.data() + off, sizeof header);
      auto& dst = corners.at(static_cast<std::size_t>(header[0])).at(static_cast<std::size_t>(header[1]));
      dst.resize(ns);
      std::memcpy(dst.data(), text.data() + off + sizeof header, ns * sizeof(float));
    }
  std::vector<float> series(stencils.size() * ns);
  for (std::size_t l = 0; l < corners.size(); ++l) {
    for (const auto& c : corners[l])
      if (c.size() != ns) throw std::logic_error("interpolate_listeners: a listener corner was recorded by no block");
    for (std::size_t k = 0; k < ns; ++k) {
      std::array<float, Stencil::kCorners> v{};
      for (int c = 0; c < Stencil::kCorners; ++c) v[static_cast<std::size_t>(c)] = corners[l][static_cast<std::size_t>(c)][k];
      series[l * ns + k] = static_cast<float>(interpolate(stencils[l], v));
    }
  }
  return series;
}

}  // namespace clatter::kernels::fdtd
