#include "petsc/pattern.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "mpi/comm.hpp"

namespace clatter::petsc {
namespace {

// (row, column) pairs for rows another rank owns, flattened per destination rank.
using Outgoing = std::vector<std::vector<PetscInt>>;

std::vector<PetscInt> exchange(MPI_Comm comm, const Outgoing& outgoing) {
  const int size = static_cast<int>(outgoing.size());
  std::vector<int> send_counts(size), recv_counts(size), send_displs(size), recv_displs(size);
  for (int r = 0; r < size; ++r) send_counts[r] = static_cast<int>(outgoing[r].size());
  mpi::check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm), "MPI_Alltoall");
  std::exclusive_scan(send_counts.begin(), send_counts.end(), send_displs.begin(), 0);
  std::exclusive_scan(recv_counts.begin(), recv_counts.end(), recv_displs.begin(), 0);
  std::vector<PetscInt> send;
  for (const auto& pairs : outgoing) send.insert(send.end(), pairs.begin(), pairs.end());
  std::vector<PetscInt> received(static_cast<std::size_t>(recv_displs.back() + recv_counts.back()));
  mpi::check(MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), MPIU_INT, received.data(),
                           recv_counts.data(), recv_displs.data(), MPIU_INT, comm),
             "MPI_Alltoallv");
  return received;
}

unsigned long long mix(unsigned long long hash, unsigned long long value) {
  // FNV-1a over 64-bit words: cheap, and only compared within one run.
  return (hash ^ value) * 1099511628211ull;
}

}  // namespace

Pattern::Pattern(const Layout& layout, std::span<const PetscInt> dofs, std::size_t dofs_per_element)
    : layout_(layout), dofs_per_element_(dofs_per_element) {
  if (dofs_per_element == 0 || dofs.size() % dofs_per_element != 0)
    throw std::invalid_argument("Pattern: " + std::to_string(dofs.size()) + " indices are not whole elements of " +
                                std::to_string(dofs_per_element));
  int size = 1;
  MPI_Comm_size(layout.comm(), &size);
  const PetscInt begin = layout.begin();
  std::vector<std::vector<PetscInt>> columns(static_cast<std::size_t>(layout.local_size()));
  Outgoing outgoing(static_cast<std::size_t>(size));
  for (std::size_t first = 0; first < dofs.size(); first += dofs_per_element) {
    auto element = dofs.subspan(first, dofs_per_element);
    for (PetscInt row : element) {
      if (row < 0) continue;
      const int owner = layout.owner(row);
      for (PetscInt column : element) {
        if (column < 0) continue;
        layout.owner(column);  // range check
        if (owner == layout.rank()) {
          columns[static_cast<std::size_t>(row - begin)].push_back(column);
        } else {
          outgoing[static_cast<std::size_t>(owner)].push_back(row);
          outgoing[static_cast<std::size_t>(owner)].push_back(column);
        }
      }
    }
  }
  const std::vector<PetscInt> received = exchange(layout.comm(), outgoing);
  for (std::size_t i = 0; i + 1 < received.size(); i += 2)
    columns[static_cast<std::size_t>(received[i] - begin)].push_back(received[i + 1]);

  diagonal_.assign(columns.size(), 0);
  off_diagonal_.assign(columns.size(), 0);
  unsigned long long hash = 14695981039346656037ull;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    auto& row = columns[i];
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    for (PetscInt column : row) {
      (layout.owns(column) ? diagonal_ : off_diagonal_)[i] += 1;
      hash = mix(mix(hash, static_cast<unsigned long long>(begin) + i), static_cast<unsigned long long>(column));
    }
  }
  mpi::check(MPI_Allreduce(&hash, &fingerprint_, 1, MPI_UNSIGNED_LONG_LONG, MPI_BXOR, layout.comm()), "MPI_Allreduce");
}

long long Pattern::local_nonzeros() const {
  return std::accumulate(diagonal_.begin(), diagonal_.end(), 0LL) +
         std::accumulate(off_diagonal_.begin(), off_diagonal_.end(), 0LL);
}

}  // namespace clatter::petsc
