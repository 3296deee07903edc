#pragma once
#include <mpi.h>

#include <array>

#include "mpi/comm.hpp"

namespace clatter::mpi {

// Half-open index range [start, start + count) of one rank's share of an axis.
struct Block {
  int start = 0;
  int count = 0;
};

// Balanced split of n cells into `parts` contiguous blocks: the first n % parts blocks get one
// extra cell. Pure arithmetic, so the layout never depends on MPI's choices.
Block block_of(int n, int parts, int index);

// A non-periodic 3D Cartesian process grid over a global cell box. Ranks are not reordered, so
// rank r always holds the same block for a given rank count (a requirement for bit-identical
// results). Dimensions come from MPI_Dims_create.
class CartTopology {
 public:
  // Throws InputError when an axis has fewer than two cells per process along it (the halo is two
  // cells deep, core/block_layout.hpp).
  CartTopology(MPI_Comm comm, std::array<int, 3> global_cells);

  MPI_Comm comm() const { return cart_.get(); }
  const std::array<int, 3>& global_cells() const { return global_; }
  const std::array<int, 3>& dims() const { return dims_; }
  const std::array<int, 3>& coords() const { return coords_; }
  std::array<int, 3> local_start() const;
  std::array<int, 3> local_count() const;
  // Neighbour rank across the face in direction `dir` (-1 or +1) of `axis`; MPI_PROC_NULL at the boundary.
  int neighbor(int axis, int dir) const;
  // Neighbour rank at `offset` (each -1, 0 or +1) in the process grid, e.g. across an edge;
  // MPI_PROC_NULL past the boundary.
  int neighbor(const std::array<int, 3>& offset) const;

 private:
  OwnedComm cart_;
  std::array<int, 3> global_{};
  std::array<int, 3> dims_{};
  std::array<int, 3> coords_{};
};

}  // namespace clatter::mpi
