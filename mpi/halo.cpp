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
  auto add = [&](int part, const std::array<int, 3>& offset, const StorageRegion& send, const StorageRegion& recv,
                 int opposite) {
    neighbor_[part] = topo.neighbor(offset);
    opposite_[part] = opposite;
    send_[part] = subarray(extent, send);
    recv_[part] = subarray(extent, recv);
    if (neighbor_[part] != MPI_PROC_NULL) bytes_ += 4LL * send.count[0] * send.count[1] * send.count[2];
  };
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      std::array<int, 3> offset{};
      offset[a] = side == 0 ? -1 : +1;
      const int f = 2 * a + side;
      add(f, offset, layout.face(a, side, false), layout.face(a, side, true), f ^ 1);
    }
  // Edges: part 6 + 4 * (axis pair) + 2 * side_a + side_b; the neighbour sends its opposite edge.
  const std::array<std::array<int, 2>, 3> pairs{{{0, 1}, {0, 2}, {1, 2}}};
  for (int p = 0; p < 3; ++p)
    for (int sa = 0; sa < 2; ++sa)
      for (int sb = 0; sb < 2; ++sb) {
        const auto [a, b] = pairs[static_cast<std::size_t>(p)];
        std::array<int, 3> offset{};
        offset[a] = sa == 0 ? -1 : +1;
        offset[b] = sb == 0 ? -1 : +1;
        const int part = 6 + 4 * p + 2 * sa + sb, opposite = 6 + 4 * p + 2 * (1 - sa) + (1 - sb);
        add(part, offset, layout.edge(a, sa, b, sb, false), layout.edge(a, sa, b, sb, true), opposite);
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
  // Part f's layers go to neighbour f with tag f; they arrive there as its opposite part.
  for (int f = 0; f < kParts; ++f) {
    check(MPI_Irecv(data, 1, recv_[f], neighbor_[f], opposite_[f], comm_, &requests_[2 * f]), "MPI_Irecv");
    check(MPI_Isend(data, 1, send_[f], neighbor_[f], f, comm_, &requests_[2 * f + 1]), "MPI_Isend");
  }
  active_ = true;
}

void HaloExchange::finish() {
  if (!active_) return;
  check(MPI_Waitall(2 * kParts, requests_.data(), MPI_STATUSES_IGNORE), "MPI_Waitall");
  active_ = false;
}

}  // namespace clatter::mpi
