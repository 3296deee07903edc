#pragma once
// How a clatter-bank subcommand plugs in: its own file declares the subcommand's options and
// returns what to run once argv is parsed. kCommands below lists them; a new job is one new file
// and one line here, and touches no other job's file.
#include <CLI/CLI.hpp>
#include <mpi.h>

#include <functional>
#include <string>

namespace clatter::jobs {

// What a running subcommand may know of the program around it.
struct JobContext {
  MPI_Comm world = MPI_COMM_NULL;
  bool is_root = false;
  int n_ranks = 1;
  std::string command_line;  // for provenance and resume hints
};

// Runs the parsed subcommand on every rank; returns the exit code (the same on every rank).
using JobRun = std::function<int(const JobContext&)>;

// A declared subcommand: run is called on every rank when app->parsed(); it reads the options
// the declaration bound (held by the closure).
struct Command {
  CLI::App* app = nullptr;
  JobRun run;
};
using AddCommand = Command (*)(CLI::App& parent);

// Every subcommand, in --help order; each is defined in the job's own file.
Command add_field_command(CLI::App& parent);     // jobs/field_job.cpp
Command add_solve_command(CLI::App& parent);     // jobs/solve_job.cpp
Command add_pan_command(CLI::App& parent);       // jobs/pan_sweep.cpp
Command add_plan_command(CLI::App& parent);      // jobs/plan.cpp
Command add_modal_command(CLI::App& parent);     // jobs/modal_sweep.cpp
Command add_modal_samples_command(CLI::App& parent);  // jobs/modal_samples.cpp
Command add_ground_command(CLI::App& parent);    // jobs/ground_sweep.cpp
Command add_merge_command(CLI::App& parent);     // jobs/merge_command.cpp
Command add_checksum_command(CLI::App& parent);  // jobs/bank_tools.cpp
Command add_info_command(CLI::App& parent);      // jobs/bank_tools.cpp
Command add_probe_command(CLI::App& parent);     // jobs/bank_tools.cpp

inline constexpr AddCommand kCommands[] = {add_field_command, add_solve_command,   add_pan_command,
                                           add_modal_command, add_modal_samples_command, add_ground_command,
                                           add_plan_command,
                                           add_merge_command,
                                           add_checksum_command, add_info_command, add_probe_command};

}  // namespace clatter::jobs
