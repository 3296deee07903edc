#pragma once
// `clatter-bank plan` for a modal sweep: per entry, the job's own pre-solve (coarse mesh, f_1 by
// inertia bracketing) gives h, the fine mesh gives the DOFs, and one inertia count on the coarse
// model at (f_max_multiple f_1)^2 gives the number of modes; one entry solved in full here
// calibrates the time per mode. Runs on this rank alone (MPI_COMM_SELF).
#include "io/config.hpp"
#include "banks/plan.hpp"

namespace clatter::jobs {

PlanEstimate modal_plan_estimate(const io::Config& config, const PlanOptions& options);

}  // namespace clatter::jobs
