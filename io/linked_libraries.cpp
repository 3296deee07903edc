#include "io/linked_libraries.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include "core/build_info.hpp"

namespace clatter::io {

std::string hdf5_library() {
  unsigned major = 0, minor = 0, release = 0;
  H5get_libversion(&major, &minor, &release);
  // The flavour is that of the headers this file was compiled against: clatter_io and clatter_io_mpi
  // each compile it against their own HDF5 install, and link that install's library.
#ifdef H5_HAVE_PARALLEL
  const char* flavour = "parallel";
#else
  const char* flavour = "serial";
#endif
  return fmt::format("{}.{}.{} ({})", major, minor, release, flavour);
}

std::string version_text(const char* program) {
  const BuildInfo& b = build_info();
  std::string text = fmt::format("{} {} (git {})\n  compiler: {} ({})\n", program, b.version, b.git_revision,
                                 b.compiler, b.build_type);
  if (const auto mpi = mpi_library()) text += fmt::format("  MPI:      {}\n", *mpi);
  text += fmt::format("  HDF5:     {}\n  Eigen:    {} (headers)\n  GSL:      {} (built against)\n", hdf5_library(), b.eigen, b.gsl);
  return text;
}

}  // namespace clatter::io
