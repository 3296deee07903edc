#include "mpi/cart.hpp"

#include <string>

namespace clatter::mpi {

Block block_of(int n, int parts, int index) {
  const int base = n / parts, extra = n % parts;
  return {index * base + (index < extra ? index : extra), base + (index < extra ? 1 : 0)};
}

CartTopology::CartTopology(MPI_Comm comm, std::array<int, 3> global_cells) : global_(global_cells) {
  const int n_ranks = size(comm);
  check(MPI_Dims_create(n_ranks, 3, dims_.data()), "MPI_Dims_create");
  for (int a = 0; a < 3; ++a)
    if (global_[a] < 2 * dims_[a])
      throw InputError("grid of " + std::to_string(global_[0]) + "x" + std::to_string(global_[1]) + "x" +
                       std::to_string(global_[2]) + " cells cannot be split over " + std::to_string(n_ranks) +
                       " ranks (" + std::to_string(dims_[a]) + " along axis " + std::to_string(a) +
                       "; each needs at least 2 cells)");
  const std::array<int, 3> periodic{0, 0, 0};
  MPI_Comm cart = MPI_COMM_NULL;
  check(MPI_Cart_create(comm, 3, dims_.data(), periodic.data(), /*reorder=*/0, &cart), "MPI_Cart_create");
  cart_ = OwnedComm(cart);
  check(MPI_Cart_coords(cart, rank(cart), 3, coords_.data()), "MPI_Cart_coords");
}

std::array<int, 3> CartTopology::local_start() const {
  std::array<int, 3> s{};
  for (int a = 0; a < 3; ++a) s[a] = block_of(global_[a], dims_[a], coords_[a]).start;
  return s;
}

std::array<int, 3> CartTopology::local_count() const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) c[a] = block_of(global_[a], dims_[a], coords_[a]).count;
  return c;
}

int CartTopology::neighbor(int axis, int dir) const {
  std::array<int, 3> offset{};
  offset[axis] = dir;
  return neighbor(offset);
}

int CartTopology::neighbor(const std::array<int, 3>& offset) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    c[a] = coords_[a] + offset[a];
    if (c[a] < 0 || c[a] >= dims_[a]) return MPI_PROC_NULL;
  }
  int r = MPI_PROC_NULL;
  check(MPI_Cart_rank(cart_.get(), c.data(), &r), "MPI_Cart_rank");
  return r;
}

}  // namespace clatter::mpi
