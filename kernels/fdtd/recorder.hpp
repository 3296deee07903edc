#pragma once
// Listener recording, split the way a decomposed solve needs it: each block records the stencil
// corners it owns, packs them for a gather, and one place interpolates every listener from all
// corners in a fixed order, so the series do not depend on how the grid was split. No MPI here:
// the caller moves the packs.
#include <array>
#include <string>
#include <vector>

#include "kernels/fdtd/listeners.hpp"
#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

class Recorder {
 public:
  // problem.field: the field being solved (mirrored corners carry its parity); layout: the block's.
  Recorder(const Problem& problem, const std::vector<std::array<double, 3>>& listeners_m, const Layout& layout,
           int n_samples);

  // Keeps sample n of every owned corner from the block's pressure (with halo, as Engine stores it).
  void record(int n, const float* pressure);
  // Whether every corner sample this block recorded at step n is finite.
  bool finite_at(int n) const;
  // This block's corners as (listener, corner, n_samples floats) records, for the gather.
  std::string pack() const;
  // Every listener's stencil, owned or not.
  const std::vector<Stencil>& stencils() const { return stencils_; }

 private:
  struct Probe {
    int listener, corner;
    long index;  // storage index in the block's layout
  };
  std::size_t n_samples_;
  std::vector<Stencil> stencils_;
  std::vector<Probe> probes_;
  std::vector<float> recorded_;  // [probe][sample]
};

// The series [listener][sample] from the packs of all blocks, which together hold every corner.
std::vector<float> interpolate_listeners(const std::vector<Stencil>& stencils, int n_samples,
                                         const std::vector<std::string>& packs);

}  // namespace clatter::kernels::fdtd
