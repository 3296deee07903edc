#pragma once
#include <mpi.h>

#include <array>

#include "mpi/cart.hpp"

namespace clatter::mpi {

// Non-blocking exchange of the six one-cell face halos of a float block stored with a one-cell
// halo on every side ((n0+2) x (n1+2) x (n2+2), last index fastest) with the Cartesian neighbours.
// Faces travel as MPI subarray datatypes, no packing copies. Edge and corner halos are not
// exchanged (a 7-point stencil never reads them). Usage: start(data); <work>; finish().
class HaloExchange {
 public:
  HaloExchange(const CartTopology& topo, const std::array<int, 3>& local_count);
  ~HaloExchange();
  HaloExchange(const HaloExchange&) = delete;
  HaloExchange& operator=(const HaloExchange&) = delete;

  void start(float* data);
  void finish();
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
