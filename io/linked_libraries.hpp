#pragma once
// What this binary actually runs with, asked at run time (for --version and /provenance).
#include <optional>
#include <string>

namespace clatter::io {

// HDF5's run-time version and flavour, e.g. "1.10.8 (parallel)".
std::string hdf5_library();
// MPI's library version line (MPI_Get_library_version); nullopt in a binary without MPI. Defined
// by io/h5_parallel.cpp in clatter_io_mpi and by io/no_mpi.cpp in the serial clatter_io.
std::optional<std::string> mpi_library();

// Multi-line "program version (git rev)\n  key: value" text for --version.
std::string version_text(const char* program);

}  // namespace clatter::io
