#include "mpi/comm.hpp"

#include <climits>
#include <stdexcept>

namespace clatter::mpi {

void check(int mpi_result, const char* call) {
  if (mpi_result == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(mpi_result, text, &length);
  throw std::runtime_error(std::string(call) + " failed: " + std::string(text, static_cast<std::size_t>(length)));
}

OwnedComm::~OwnedComm() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (comm_ != MPI_COMM_NULL && !finalized) MPI_Comm_free(&comm_);
}

OwnedComm& OwnedComm::operator=(OwnedComm&& other) noexcept {
  if (this != &other) {
    OwnedComm old(std::exchange(comm_, std::exchange(other.comm_, MPI_COMM_NULL)));
  }
  return *this;
}

int rank(MPI_Comm comm) {
  int r = 0;
  check(MPI_Comm_rank(comm, &r), "MPI_Comm_rank");
  return r;
}

int size(MPI_Comm comm) {
  int s = 0;
  check(MPI_Comm_size(comm, &s), "MPI_Comm_size");
  return s;
}

std::string broadcast(MPI_Comm comm, std::string text, int root) {
  if (text.size() > static_cast<std::size_t>(INT_MAX)) throw std::length_error("broadcast: text over 2 GiB");
  int length = static_cast<int>(text.size());
  check(MPI_Bcast(&length, 1, MPI_INT, root, comm), "MPI_Bcast");
  text.resize(static_cast<std::size_t>(length));
  check(MPI_Bcast(text.data(), length, MPI_CHAR, root, comm), "MPI_Bcast");
  return text;
}

std::vector<std::string> gather(MPI_Comm comm, const std::string& text, int root) {
  const int n = size(comm);
  const bool is_root = rank(comm) == root;
  int length = static_cast<int>(text.size());
  std::vector<int> lengths(is_root ? static_cast<std::size_t>(n) : 0);
  check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, root, comm), "MPI_Gather");
  std::vector<int> offsets(lengths.size());
  std::string all;
  if (is_root) {
    long long total = 0;
    for (std::size_t i = 0; i < lengths.size(); ++i) {
      offsets[i] = static_cast<int>(total);
      total += lengths[i];
    }
    if (total > INT_MAX) throw std::length_error("gather: texts over 2 GiB in all");
    all.resize(static_cast<std::size_t>(total));
  }
  check(MPI_Gatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, root, comm),
        "MPI_Gatherv");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < lengths.size(); ++i)
    out.push_back(all.substr(static_cast<std::size_t>(offsets[i]), static_cast<std::size_t>(lengths[i])));
  return out;
}

namespace detail {
void agree_on(MPI_Comm comm, int local_code, const std::string& local_message) {
  // The lowest failing rank speaks for everyone.
  const int me = rank(comm);
  int candidate = local_code != kExitOk ? me : INT_MAX;
  int speaker = INT_MAX;
  check(MPI_Allreduce(&candidate, &speaker, 1, MPI_INT, MPI_MIN, comm), "MPI_Allreduce");
  if (speaker == INT_MAX) return;
  int code = local_code;
  check(MPI_Bcast(&code, 1, MPI_INT, speaker, comm), "MPI_Bcast");
  std::string message = broadcast(comm, me == speaker ? local_message : std::string(), speaker);
  throw CollectiveError(message, code);
}
}  // namespace detail

}  // namespace clatter::mpi
