#include "mpi/halo.hpp"

namespace clatter::mpi {

HaloExchange::HaloExchange(const CartTopology& topo, const std::array<int, 3>& n) : comm_(topo.comm()) {
  const int sizes[3] = {n[0] + 2, n[1] + 2, n[2] + 2};
  for (int a = 0; a < 3; ++a) {
    neighbor_[2 * a] = topo.neighbor(a, -1);
    neighbor_[2 * a + 1] = topo.neighbor(a, +1);
    int sub[3] = {n[0], n[1], n[2]};
    sub[a] = 1;
    for (int side = 0; side < 2; ++side) {
      int send_start[3] = {1, 1, 1}, recv_start[3] = {1, 1, 1};
      send_start[a] = side == 0 ? 1 : n[a];     // first or last owned layer
      recv_start[a] = side == 0 ? 0 : n[a] + 1;  // low or high halo layer
      MPI_Datatype& s = send_[2 * a + side];
      MPI_Datatype& r = recv_[2 * a + side];
      check(MPI_Type_create_subarray(3, sizes, sub, send_start, MPI_ORDER_C, MPI_FLOAT, &s), "MPI_Type_create_subarray");
      check(MPI_Type_create_subarray(3, sizes, sub, recv_start, MPI_ORDER_C, MPI_FLOAT, &r), "MPI_Type_create_subarray");
      MPI_Type_commit(&s);
      MPI_Type_commit(&r);
      if (neighbor_[2 * a + side] != MPI_PROC_NULL) bytes_ += 4LL * sub[0] * sub[1] * sub[2];
    }
  }
  requests_.fill(MPI_REQUEST_NULL);
}

HaloExchange::~HaloExchange() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) return;
  for (auto& t : send_) MPI_Type_free(&t);
  for (auto& t : recv_) MPI_Type_free(&t);
}

void HaloExchange::start(float* data) {
  // Face f's layer goes to neighbour f with tag f; it arrives as the opposite face (f ^ 1) there.
  for (int f = 0; f < 6; ++f) {
    check(MPI_Irecv(data, 1, recv_[f], neighbor_[f], f ^ 1, comm_, &requests_[2 * f]), "MPI_Irecv");
    check(MPI_Isend(data, 1, send_[f], neighbor_[f], f, comm_, &requests_[2 * f + 1]), "MPI_Isend");
  }
  active_ = true;
}

void HaloExchange::finish() {
  if (!active_) return;
  check(MPI_Waitall(12, requests_.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  active_ = false;
}

}  // namespace clatter::mpi
