#pragma once
#include <stdexcept>
#include <string>

namespace clatter {

// Process exit codes shared by every Clatter command (documented in docs/architecture.md).
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,      // a run-time failure (I/O, numerics, a bug)
  kExitInputError = 2,   // bad command line, config, scene, mesh or bank: fix the input
};

// Bad user input. Its message is one line naming the file, key and value; it ends the run with
// kExitInputError. Raised identically on every rank (inputs are broadcast before validation), so
// rank 0 alone prints it and no rank needs to abort the others.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace clatter
