// The serial clatter_io's answer: this binary links no MPI library.
#include "io/linked_libraries.hpp"

namespace clatter::io {

std::optional<std::string> mpi_library() { return std::nullopt; }

}  // namespace clatter::io
