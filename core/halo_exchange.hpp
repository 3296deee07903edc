#pragma once
// How a block's stepper gets its halo filled, without knowing who fills it (MPI ranks in mpi/, a
// serial copy between blocks in tests, nothing at all for a single block). The data is stored as
// core/block_layout.hpp says. Usage per step: start(data); <work that reads no halo>; finish().
namespace clatter {

class HaloExchange {
 public:
  virtual ~HaloExchange() = default;
  // Begins filling the halo of `data` from the neighbours' owned faces; the owned cells of `data`
  // must not change until finish() returns.
  virtual void start(float* data) = 0;
  // Returns once the halo of the data given to start() holds the neighbours' values.
  virtual void finish() = 0;
};

// One block holds the whole grid: there is no neighbour, so no halo to fill.
class NoHaloExchange final : public HaloExchange {
 public:
  void start(float*) override {}
  void finish() override {}
};

}  // namespace clatter
