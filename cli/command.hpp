#pragma once
// How a clatter-bank subcommand plugs in: the code that declares it binds its options and returns
// what to run once argv is parsed. The bank kinds' subcommands come from the registry
// (banks/registry.hpp); the others (field, plan, merge, info, probe, checksum) are listed in
// banks/bank_main.cpp.
#include <CLI/CLI.hpp>
#include <mpi.h>

#include <functional>
#include <string>

namespace clatter::jobs {

// What a running subcommand knows of the program around it: the one run context, filled from
// the global options once argv is parsed.
struct RunContext {
  MPI_Comm world = MPI_COMM_NULL;
  bool is_root = false;
  int n_ranks = 1;
  std::string command_line;         // for provenance and resume hints
  double progress_interval_s = 10;  // --progress-interval: seconds between a long stage's progress lines (0: none)
};

// Runs the parsed subcommand on every rank; returns the exit code (the same on every rank).
using JobRun = std::function<int(const RunContext&)>;

// A declared subcommand: run is called on every rank when app->parsed(); it reads the options
// the declaration bound (held by the closure).
struct Command {
  CLI::App* app = nullptr;
  JobRun run;
};

}  // namespace clatter::jobs
