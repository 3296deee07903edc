#pragma once
#include <mpi.h>

#include <string>

namespace clatter::petsc {

// PETSc and SLEPc for one process, inside an mpi::Session (MPI is already up; PETSc neither
// initialises nor finalises it). Constructed once per process; SLEPc and PETSc are finalised in
// that order on destruction, so every Matrix, Vector and solve must be gone by then.
//
// What it keeps away from Clatter:
//  - options from outside Clatter's config: ~/.petscrc, ./.petscrc and ./petscrc are skipped, and
//    PETSC_OPTIONS / PETSC_OPTIONS_YAML are hidden from PetscInitialize (and put back after);
//    `ignored_environment()` names what was hidden so the caller can warn. Solver settings live in
//    per-solve options databases (options.hpp), never in the global one.
//  - signals: PETSc installs no signal handler (-no_signal_handler), so SIGTERM/SIGINT stay with
//    core/interrupt.hpp;
//  - error printing: a handler records PETSc's message for `check()` instead of printing a
//    traceback on every rank.
// PETSc's event log runs (PetscLogDefaultBegin) so a solve can report its factorisation times.
class Session {
 public:
  explicit Session(MPI_Comm world = MPI_COMM_WORLD);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // "PETSC_OPTIONS=..." lines for what was set in the environment and not read; empty if none.
  const std::string& ignored_environment() const { return ignored_environment_; }
  // "PETSc 3.18.5, SLEPc 3.18.2": the libraries this process runs with.
  static std::string versions();

 private:
  std::string ignored_environment_;
};

}  // namespace clatter::petsc
