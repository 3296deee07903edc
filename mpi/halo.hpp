#pragma once
#include <mpi.h>

#include <array>

#include "core/block_layout.hpp"
#include "core/halo_exchange.hpp"
#include "mpi/cart.hpp"

namespace clatter::mpi {

// Non-blocking exchange of the six one-cell face halos of a float block stored as `layout` says
// (core/block_layout.hpp) with the Cartesian neighbours. Faces travel as MPI subarray datatypes
// built from the layout's own face regions, no packing copies.
class HaloExchange final : public clatter::HaloExchange {
 public:
  HaloExchange(const CartTopology& topo, const BlockLayout& layout);
  ~HaloExchange() override;
  HaloExchange(const HaloExchange&) = delete;
  HaloExchange& operator=(const HaloExchange&) = delete;

  void start(float* data) override;
  void finish() override;
  // Bytes sent per exchange by this rank.
  long long bytes_per_exchange() const { return bytes_; }

 private:
  MPI_Comm comm_;
  std::array<int, 6> neighbor_{};  // -x, +x, -y, +y, -z, +z
  std::array<MPI_Datatype, 6> send_{}, recv_{};
  std::array<MPI_Request, 12> requests_{};
  long long bytes_ = 0;
  bool active_ = false;
};

}  // namespace clatter::mpi
