#pragma once
#include <mpi.h>

#include <array>

#include "core/block_layout.hpp"
#include "core/halo_exchange.hpp"
#include "mpi/cart.hpp"

namespace clatter::mpi {

// Non-blocking exchange of the halo of a float block stored as `layout` says
// (core/block_layout.hpp): the six two-cell faces with the face neighbours and the twelve one-cell
// edges with the edge (diagonal) neighbours, all posted at once. They travel as MPI subarray
// datatypes built from the layout's own face and edge regions, no packing copies.
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
  static constexpr int kParts = 18;       // 6 faces, then 12 edges
  std::array<int, kParts> neighbor_{};     // faces: -x, +x, -y, +y, -z, +z
  std::array<int, kParts> opposite_{};     // the part index under which the neighbour sends to us
  std::array<MPI_Datatype, kParts> send_{}, recv_{};
  std::array<MPI_Request, 2 * kParts> requests_{};
  long long bytes_ = 0;
  bool active_ = false;
};

}  // namespace clatter::mpi
