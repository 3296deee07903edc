#pragma once
// Files shared by the ranks of an MPI communicator, written through MPI-IO. Only in clatter_io_mpi
// (built against the parallel HDF5); serial programs see io/h5.hpp alone.
#include <mpi.h>

#include "io/h5.hpp"

namespace clatter::io {

// File::create over `comm`: every rank of `comm` calls it, and every write of a dataset or
// attribute, commit() and destruction are collective over `comm`, which must outlive the file.
File create_parallel(const std::string& path, MPI_Comm comm);

// Collective on a parallel file: every rank writes its block [offset, offset + count) of a dataset
// of `global_dims` in one collective MPI-IO call. A rank may own an empty block. On a serial file
// the one process writes one block.
template <Element T>
void write_dataset_block(File& file, const std::string& name, const Dims& global_dims, const Dims& offset,
                         const Dims& count, std::span<const T> data, std::string_view units, bool compress = false);

}  // namespace clatter::io
