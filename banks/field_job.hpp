#pragma once
#include <mpi.h>

#include <string>

#include "io/config.hpp"

namespace clatter::jobs {

// `clatter-bank field`: samples the exact free-space pressure of a point monopole driven by the
// pulse psi(t; h) on a cubic grid split over the ranks (Cartesian blocks) and writes it to one
// HDF5 file with a collective MPI-IO write. It exercises every layer a bank solve uses (config,
// decomposition, kernels, parallel HDF5, provenance, stage timing), and its output is the exact
// reference field the FDTD solver is validated against. Format: docs/formats.md.
const io::Schema& field_schema();

inline constexpr const char* kFieldFormat = "clatter-field";
inline constexpr int kFieldFormatVersion = 2;

void run_field(MPI_Comm comm, const io::Config& config, const std::string& out_path, const std::string& command);

}  // namespace clatter::jobs
