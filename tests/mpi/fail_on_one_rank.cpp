// Rank 1 throws while rank 0 waits in a collective; both hold an open parallel output file.
// Without mpi::run's abort this would hang forever (tests/cli/expect_abort.sh checks it does not).
#include <stdexcept>
#include <string>

#include "io/h5_parallel.hpp"
#include "mpi/session.hpp"

int main(int argc, char** argv) {
  return clatter::mpi::run(argc, argv, "fail-on-one-rank", [&](clatter::mpi::Session& session) {
    const std::string dir = argc > 1 ? argv[1] : ".";
    auto file = clatter::io::create_parallel(dir + "/partial.h5", session.world());
    std::vector<double> x(1000, 1.0);
    clatter::io::write_dataset<double>(file, "/x", x, {1000}, "m");
    if (session.rank() == 1) throw std::runtime_error("injected failure on rank 1");
    MPI_Barrier(session.world());  // rank 1 never arrives
    file.commit();
    return 0;
  });
}
