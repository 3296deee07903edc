#pragma once
// `clatter-bank modal-samples`: the adaptive sampling of the ellipsoid patch by coarse FEM solves
// (003 section 5.3), written as a [patch] table for a modal config.
#include "cli/command.hpp"

namespace clatter::jobs {

Command add_modal_samples_command(CLI::App& parent);

}  // namespace clatter::jobs
