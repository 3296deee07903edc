#pragma once
#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace clatter::mpi {

// Throws std::runtime_error naming the call when an MPI function returns an error.
void check(int mpi_result, const char* call);

// Owns a communicator created by a split or a topology call and frees it on destruction.
class OwnedComm {
 public:
  OwnedComm() = default;
  explicit OwnedComm(MPI_Comm comm) : comm_(comm) {}
  ~OwnedComm();
  OwnedComm(OwnedComm&& other) noexcept : comm_(std::exchange(other.comm_, MPI_COMM_NULL)) {}
  OwnedComm& operator=(OwnedComm&& other) noexcept;
  OwnedComm(const OwnedComm&) = delete;
  OwnedComm& operator=(const OwnedComm&) = delete;
  MPI_Comm get() const { return comm_; }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
};

int rank(MPI_Comm comm);
int size(MPI_Comm comm);

std::string broadcast(MPI_Comm comm, std::string text, int root = 0);
// On root: every rank's string, indexed by rank; elsewhere: empty.
std::vector<std::string> gather(MPI_Comm comm, const std::string& text, int root = 0);

// An error every rank of a communicator agreed on: the message of the lowest failing rank.
class CollectiveError : public std::runtime_error {
 public:
  CollectiveError(const std::string& message, int exit_code) : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

// Runs `f` on every rank of `comm`. If it throws on any rank, every rank throws CollectiveError
// with the lowest failing rank's message, so all ranks leave together and nobody waits forever
// in a later collective. The exit code is kExitInputError for an InputError, else kExitFailure.
template <class F>
void agree(MPI_Comm comm, F&& f);

namespace detail {
void agree_on(MPI_Comm comm, int local_code, const std::string& local_message);
}

template <class F>
void agree(MPI_Comm comm, F&& f) {
  int code = kExitOk;
  std::string message;
  try {
    std::forward<F>(f)();
  } catch (const InputError& e) {
    code = kExitInputError;
    message = e.what();
  } catch (const std::exception& e) {
    code = kExitFailure;
    message = e.what();
  }
  detail::agree_on(comm, code, message);
}

}  // namespace clatter::mpi
