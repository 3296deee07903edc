#pragma once
// `clatter-bank plan` of a PAN sweep: the tasks, cells x steps per task, memory per rank and the
// time per task from a calibration solve measured on this machine (serial: MPI_COMM_SELF), for
// proxies and for mesh entries alike.
#include "banks/pan/pan_spec.hpp"
#include "banks/plan.hpp"

namespace clatter::jobs {

// The pan kind's params, or pan-object's with the scene's meshes read (read_scene_meshes): an entry
// of eight octants costs its full domain and eight octants' hearing.
PlanEstimate pan_plan_estimate(const PanParams& params, const PlanOptions& options);

}  // namespace clatter::jobs
