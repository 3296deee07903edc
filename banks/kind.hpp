#pragma once
// A bank kind: everything clatter-bank knows of one kind of soundbank (PAN, modal, ground), as one
// interface. The registry (banks/registry.hpp) lists the kinds; the program makes each kind's
// subcommand (`clatter-bank NAME -c ...`) and the shared ones (`merge`, `plan`, `info`, `probe`)
// from it, so no code outside the kind's folder names the kind.
//
// A kind's pieces, in the order a sweep uses them: its config schema; the spec it validates the
// config into and the task list the spec implies, one task's computation, the merge of the task
// files into the bank model and its writer (all four given to the sweep engine as a BankSweep);
// and, reading a bank back, `info`, `probe` and `plan`.
#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "banks/plan.hpp"
#include "cli/command.hpp"
#include "cli/run_options.hpp"
#include "io/config.hpp"
#include "sweep/bank_sweep.hpp"

namespace clatter::jobs {

// Serial reading of a bank file of this kind (rank 0 prints the text). `options` are those the
// kind declared on the subcommand: the program refuses them for a file of another kind.
struct FileTool {
  std::vector<CLI::Option*> options;
  std::function<std::string(const std::string& path)> run;  // empty: the kind has no such tool
};

// What `probe` asks of every kind: the listener and the proxy's scale (the kind declares the rest).
struct ProbePoint {
  std::array<double, 3> point_m{};
  double scale = 1.0;
};

class BankKind {
 public:
  virtual ~BankKind() = default;

  // The subcommand, the manifest's `kind` and the log prefix: "pan".
  virtual const char* name() const = 0;
  virtual const char* description() const = 0;  // the subcommand's --help line
  virtual const char* default_out() const = 0;   // -o's default
  // The bank file's `format` attribute: how `info` and `probe` know a file's kind.
  virtual const char* file_format() const = 0;

  virtual const io::Schema& schema() const = 0;
  // The config run without -c/--config; null: the schema's defaults.
  virtual const BuiltinConfig* builtin_config() const { return nullptr; }

  // The sweep of a config (validated here: InputError naming key and value), the same on every
  // rank. Called again by `merge` on the config a results folder recorded.
  virtual BankSweep sweep(const io::Config& config, const RunContext& context) const = 0;
  // Held on every rank while the kind's sweep or plan runs (the modal kind's PETSc session).
  virtual std::shared_ptr<void> start_libraries(const RunContext&) const { return nullptr; }

  // `info FILE`: declares the kind's own options on the subcommand.
  virtual FileTool info(CLI::App& info) const = 0;
  // `probe FILE`: the field at `point`; declares the kind's own options. Default: none.
  virtual FileTool probe(CLI::App& probe, const ProbePoint& point) const;
  // `plan -c CONFIG`: the predicted cost of the sweep, on rank 0 alone. Default: InputError.
  virtual PlanEstimate plan(const io::Config& config, const PlanOptions& options) const;
  // Subcommands of the kind beside its sweep (pan: `solve`; modal: `modal-samples`).
  virtual std::vector<Command> more_commands(CLI::App& parent) const { (void)parent; return {}; }
};

}  // namespace clatter::jobs
