#pragma once

namespace clatter {

// What this binary was built from, fixed at configure and build time. The libraries it runs with
// (HDF5, MPI) are asked at run time by io/linked_libraries.hpp, which prints --version.
struct BuildInfo {
  const char* version;
  const char* git_revision;
  const char* compiler;
  const char* build_type;
  const char* eigen;  // header-only, compiled into the kernels
  const char* gsl;    // the headers the kernels were compiled against
};

const BuildInfo& build_info();
const char* git_revision();

}  // namespace clatter
