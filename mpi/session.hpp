#pragma once
#include <mpi.h>

#include <functional>

namespace clatter::mpi {

// The MPI lifetime of one process: MPI_Init_thread (funneled) on construction, MPI_Finalize on
// destruction. Exactly one per program, created first in main.
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  MPI_Comm world() const { return MPI_COMM_WORLD; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }

 private:
  int rank_ = 0;
  int size_ = 1;
};

// Runs `body` inside a Session and turns every way it can fail into a prompt, clean exit:
//  - a CollectiveError (all ranks agree, see agree()): rank 0 prints it, every rank returns its
//    exit code through MPI_Finalize;
//  - any other exception on any rank: that rank prints "program: error on rank r/n: message" once,
//    removes registered temporary files, and MPI_Abort ends every rank with the exit code
//    (kExitInputError for an InputError, else kExitFailure) - never a hang.
int run(int argc, char** argv, const char* program, const std::function<int(Session&)>& body);

}  // namespace clatter::mpi
