#include "mpi/halo.hpp"

namespace clatter::mpi {

namespace {
MPI_Datatype subarray(const std::array<int, 3>& extent, const StorageRegion& region) {
  MPI_Datatype t;
  check(MPI_Type_create_subarray(3, extent.data(), region.count.data(), region.start.data(), MPI_ORDER_C, MPI_FLOAT, &t),
        "MPI_Type_create_subarray");
  check(MPI_Type_commit(&t), "MPI_Type_commit");
  return t;
}
}  // namespace

HaloExchange::HaloExchange(const CartTopology& topo, const BlockLayout& layout) : comm_(topo.comm()) {
  const auto extent = layout.extent();
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int f = 2 * a + side;
      neighbor_[f] = topo.neighbor(a, side == 0 ? -1 : +1);
      const StorageRegion face = layout.face(a, side, false);
      send_[f] = subarray(extent, face);
      recv_[f] = subarray(extent, layout.face(a, side, true));
      if (neighbor_[f] != MPI_PROC_NULL) bytes_ += 4LL * face.count[0] * face.count[1] * face.count[2];
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
