#pragma once
// `clatter-bank plan` of a PAN sweep: the tasks, cells x steps per task, memory per rank and the
// time per task from a calibration solve measured on this machine (serial: MPI_COMM_SELF).
#include "banks/plan.hpp"
#include "io/config.hpp"

namespace clatter::jobs {

PlanEstimate pan_plan_estimate(const io::Config& config, const PlanOptions& options);

}  // namespace clatter::jobs
