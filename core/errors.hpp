#pragma once
#include <stdexcept>
#include <string>

namespace clatter {

// Process exit codes shared by every Clatter command (documented in docs/architecture.md).
enum ExitCode : int {
  kExitOk = 0,
  kExitFailure = 1,      // a run-time failure (I/O, numerics, a bug)
  kExitInputError = 2,   // bad command line, config, scene, mesh or bank: fix the input
  kExitInterrupted = 3,  // stopped by SIGTERM/SIGINT between or inside tasks: run again with --resume
  kExitTasksFailed = 4,  // a sweep finished, but some tasks failed (listed by clatter-bank info)
};

// Bad user input. Its message is one line naming the file, key and value; it ends the run with
// kExitInputError. Raised identically on every rank (inputs are broadcast before validation), so
// rank 0 alone prints it and no rank needs to abort the others.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One task of a sweep cannot be done (unstable solve, I/O error writing its result): the sweep
// records the reason and goes on. Raised identically on every rank of the task's group.
class TaskFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// SIGTERM or SIGINT arrived (core/interrupt.hpp); raised identically on every rank of a group.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace clatter
