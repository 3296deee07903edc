#pragma once
#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace clatter::petsc {

// A PETSc or SLEPc call that failed: PETSc's own message (where it was raised, and why).
class Error : public std::runtime_error {
 public:
  Error(const std::string& message, PetscErrorCode code) : std::runtime_error(message), code_(code) {}
  PetscErrorCode code() const { return code_; }

 private:
  PetscErrorCode code_;
};

// Throws Error naming `what` and PETSc's message when `code` is not 0. The message is the one the
// Session's error handler captured when the error was first raised (PETSc prints nothing itself).
void check(PetscErrorCode code, const char* what);

}  // namespace clatter::petsc
