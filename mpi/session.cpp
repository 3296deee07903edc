#include "mpi/session.hpp"

#include <cstdio>
#include <exception>

#include "core/cleanup.hpp"
#include "core/errors.hpp"
#include "mpi/comm.hpp"

namespace clatter::mpi {

Session::Session(int& argc, char**& argv) {
  int provided = 0;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Session::~Session() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

namespace {
// One rank failed on its own: report it once and take every rank down. With a single rank there is
// nobody to abort, so it returns the code and the Session finalizes normally.
int fail(const Session& session, const char* program, const char* message, int code) {
  if (session.size() > 1)
    std::fprintf(stderr, "%s: error on rank %d of %d: %s\n", program, session.rank(), session.size(), message);
  else
    std::fprintf(stderr, "%s: error: %s\n", program, message);
  std::fflush(stderr);
  remove_registered_temporaries();
  if (session.size() > 1) MPI_Abort(MPI_COMM_WORLD, code);
  return code;
}
}  // namespace

int run(int argc, char** argv, const char* program, const std::function<int(Session&)>& body) {
  Session session(argc, argv);
  try {
    return body(session);
  } catch (const CollectiveError& e) {
    if (session.is_root()) std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    remove_registered_temporaries();
    return e.exit_code();
  } catch (const InputError& e) {
    return fail(session, program, e.what(), kExitInputError);
  } catch (const std::exception& e) {
    return fail(session, program, e.what(), kExitFailure);
  } catch (...) {
    return fail(session, program, "unknown exception", kExitFailure);
  }
}

}  // namespace clatter::mpi
