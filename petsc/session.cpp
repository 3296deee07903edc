#include "petsc/session.hpp"

#include <slepcsys.h>

#include <cstdlib>
#include <stdexcept>
#include <utility>
#include <vector>

#include "petsc/error.hpp"

namespace clatter::petsc {
namespace {

// PETSc has one global state per process and cannot start again after PetscFinalize.
bool g_started = false;
std::string g_last_error;

// Replaces PETSc's traceback printer: keeps the first (innermost) message of an error for check().
PetscErrorCode record_error(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                            PetscErrorType kind, const char* message, void*) {
  if (kind != PETSC_ERROR_INITIAL) return code;
  try {
    g_last_error = std::string(message ? message : "") + " (" + (function ? function : "?") + " at " +
                   (file ? file : "?") + ":" + std::to_string(line) + ")";
  } catch (...) {
    // Out of memory while reporting: the code alone still reaches check().
  }
  return code;
}

// PetscInitialize reads these on rank 0 whatever its arguments say.
const char* const kEnvironmentOptions[] = {"PETSC_OPTIONS", "PETSC_OPTIONS_YAML"};

// PETSc keeps pointers into argv for the life of the process.
char g_arg0[] = "clatter";
char g_arg1[] = "-skip_petscrc";
char g_arg2[] = "-no_signal_handler";
char* g_argv_storage[] = {g_arg0, g_arg1, g_arg2, nullptr};

}  // namespace

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* generic = nullptr;
  PetscErrorMessage(code, &generic, nullptr);
  std::string message = std::string(what) + " failed: PETSc error " + std::to_string(code);
  if (generic) message += " (" + std::string(generic) + ")";
  if (!g_last_error.empty()) message += ": " + std::exchange(g_last_error, {});
  throw Error(message, code);
}

Session::Session(MPI_Comm world) {
  if (g_started) throw std::logic_error("petsc::Session: PETSc is initialised once per process");
  int mpi_up = 0;
  MPI_Initialized(&mpi_up);
  if (!mpi_up) throw std::logic_error("petsc::Session: create the mpi::Session first");

  std::vector<std::pair<const char*, std::string>> hidden;
  for (const char* name : kEnvironmentOptions) {
    if (const char* value = std::getenv(name)) {
      hidden.emplace_back(name, value);
      ignored_environment_ += std::string(name) + "=" + value + "\n";
      unsetenv(name);
    }
  }
  PETSC_COMM_WORLD = world;
  int argc = 3;
  char** argv = g_argv_storage;
  PetscErrorCode code = SlepcInitialize(&argc, &argv, nullptr, nullptr);
  for (const auto& [name, value] : hidden) setenv(name, value.c_str(), 1);
  check(code, "SlepcInitialize");
  g_started = true;
  check(PetscPushErrorHandler(record_error, nullptr), "PetscPushErrorHandler");
  check(PetscLogDefaultBegin(), "PetscLogDefaultBegin");
}

Session::~Session() {
  // SlepcFinalize finalises PETSc too (SLEPc initialised it); MPI stays up for mpi::Session.
  PetscPopErrorHandler();
  SlepcFinalize();
}

std::string Session::versions() {
  // Run-time numbers, not the headers' macros: a module may swap the shared library.
  PetscInt p[3] = {}, s[3] = {};
  check(PetscGetVersionNumber(&p[0], &p[1], &p[2], nullptr), "PetscGetVersionNumber");
  check(SlepcGetVersionNumber(&s[0], &s[1], &s[2], nullptr), "SlepcGetVersionNumber");
  auto dotted = [](const PetscInt* v) {
    return std::to_string(v[0]) + "." + std::to_string(v[1]) + "." + std::to_string(v[2]);
  };
  return "PETSc " + dotted(p) + ", SLEPc " + dotted(s);
}

}  // namespace clatter::petsc
