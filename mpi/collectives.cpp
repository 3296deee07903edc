#include "mpi/collectives.hpp"

#include <string>

namespace clatter::mpi {
namespace detail {

int byte_count(std::uint64_t count, std::size_t item_bytes, const char* what) {
  if (item_bytes != 0 && count > static_cast<std::uint64_t>(INT_MAX) / item_bytes)
    throw std::length_error(std::string(what) + ": over INT_MAX bytes in one MPI call");
  return static_cast<int>(count * item_bytes);
}

void broadcast_bytes(MPI_Comm comm, void* data, int bytes, int root) {
  check(MPI_Bcast(data, bytes, MPI_BYTE, root, comm), "MPI_Bcast");
}

std::uint64_t broadcast_count(MPI_Comm comm, std::uint64_t count, int root) {
  check(MPI_Bcast(&count, 1, MPI_UINT64_T, root, comm), "MPI_Bcast");
  return count;
}

std::vector<std::uint64_t> gather_bytes(MPI_Comm comm, const void* data, std::uint64_t count, std::size_t item_bytes,
                                        std::vector<unsigned char>& all, int root) {
  // Every rank learns every count, so a total past INT_MAX throws on all of them, not on root
  // alone while the others wait in the Gatherv.
  const std::vector<std::uint64_t> counts = all_gather(comm, count);
  std::uint64_t total = 0;
  for (const std::uint64_t n : counts) total += n;
  byte_count(total, item_bytes, "gather");
  const bool is_root = rank(comm) == root;
  std::vector<int> bytes, offsets;
  if (is_root) {
    int at = 0;
    for (const std::uint64_t n : counts) {
      bytes.push_back(static_cast<int>(n * item_bytes));
      offsets.push_back(at);
      at += bytes.back();
    }
    all.resize(static_cast<std::size_t>(at));
  }
  check(MPI_Gatherv(data, static_cast<int>(count * item_bytes), MPI_BYTE, all.data(), bytes.data(), offsets.data(),
                    MPI_BYTE, root, comm),
        "MPI_Gatherv");
  return is_root ? counts : std::vector<std::uint64_t>{};
}

void all_gather_bytes(MPI_Comm comm, const void* data, int bytes, void* all) {
  check(MPI_Allgather(data, bytes, MPI_BYTE, all, bytes, MPI_BYTE, comm), "MPI_Allgather");
}

void all_reduce(MPI_Comm comm, const void* in, void* out, std::size_t count, MPI_Datatype type, MPI_Op op) {
  if (count > static_cast<std::size_t>(INT_MAX)) throw std::length_error("all_reduce: over INT_MAX elements");
  check(MPI_Allreduce(in, out, static_cast<int>(count), type, op, comm), "MPI_Allreduce");
}

}  // namespace detail

bool any(MPI_Comm comm, bool value) {
  const int local = value ? 1 : 0;
  int result = 0;
  check(MPI_Allreduce(&local, &result, 1, MPI_INT, MPI_LOR, comm), "MPI_Allreduce");
  return result != 0;
}

}  // namespace clatter::mpi
