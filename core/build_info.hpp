#pragma once
#include <string>

namespace clatter {

// What this binary was built from and against; printed by --version and stored as provenance.
struct BuildInfo {
  const char* version;
  const char* git_revision;
  const char* compiler;
  const char* build_type;
  const char* mpi;
  const char* petsc;
  const char* slepc;
  const char* hdf5;
  const char* eigen;
  const char* gsl;
  const char* cgal;
};

const BuildInfo& build_info();
const char* git_revision();

// Multi-line "name version\n  key: value" text for --version.
std::string version_text(const char* program);

}  // namespace clatter
