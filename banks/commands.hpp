#pragma once
// The subcommands of clatter-bank, in --help order: `field`; per bank kind of the registry its
// sweep (`pan`, `modal`, `ground`) and its own extras (`solve`, `modal-samples`); then the
// subcommands every kind shares: `plan`, `merge`, `info`, `probe`, `checksum`.
#include <CLI/CLI.hpp>

#include <vector>

#include "banks/kind.hpp"
#include "cli/command.hpp"

namespace clatter::jobs {

std::vector<Command> add_commands(CLI::App& app);

Command add_field_command(CLI::App& parent);    // banks/field_job.cpp
Command add_sweep_command(CLI::App& parent, const BankKind& kind);  // banks/commands.cpp, and below
Command add_plan_command(CLI::App& parent);     // banks/plan_command.cpp
Command add_merge_command(CLI::App& parent);
Command add_info_command(CLI::App& parent);
Command add_probe_command(CLI::App& parent);
Command add_checksum_command(CLI::App& parent);

}  // namespace clatter::jobs
