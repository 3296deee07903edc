#include <fmt/format.h>

#include "core/build_info.hpp"

namespace clatter {

std::string version_text(const char* program) {
  const BuildInfo& b = build_info();
  return fmt::format(
      "{} {} (git {})\n"
      "  compiler: {} ({})\n"
      "  MPI:      {}\n"
      "  PETSc:    {}\n"
      "  SLEPc:    {}\n"
      "  HDF5:     {}\n"
      "  Eigen:    {}\n"
      "  GSL:      {}\n"
      "  CGAL:     {}\n",
      program, b.version, b.git_revision, b.compiler, b.build_type, b.mpi, b.petsc, b.slepc, b.hdf5, b.eigen, b.gsl,
      b.cgal);
}

}  // namespace clatter
