#pragma once
// One entry of the object bank (003 §5.4's direct path): the object's own mesh, in its body frame
// (the mesh's axes about its centre of mass), filled with quadratic tetrahedra at h from the shear
// wavelength at f_max and the thinnest part, K and M assembled on the task group, every mode in
// [f_1, f_max] solved as the ellipsoid bank solves them (count check, rigid motions removed, the
// basis rule), the shapes on the surface and every mode's transfer for an arbitrary shape.
#include <mpi.h>

#include <string>

#include "banks/modal/object_spec.hpp"
#include "model/object_bank.hpp"
#include "sweep/sweep.hpp"

namespace clatter::jobs {

// Collective on `group`; the full entry on the group's rank 0, an empty one elsewhere. Throws
// TaskFailure (mesh, count check, residual) or Interrupted, alike on every rank.
// with_transfer false leaves the transfer out (an entry no bank may hold: checks of the modes alone,
// which would otherwise spend nearly all their time on it).
model::ObjectEntry build_object_entry(MPI_Comm group, const ObjectSpec& spec, std::size_t object,
                                      bool with_transfer = true);

TaskWriter run_object_task(MPI_Comm group, const ObjectSpec& spec, const ObjectTask& task);

model::ObjectBank merge_object_results(const ObjectSpec& spec, const std::string& results_dir,
                                       const std::string& config_toml);

// The edge length the object is meshed at before the thickness cap: c_s / f_max / elements_per_wavelength.
double object_edge_length_m(const ObjectSpec& spec, const model::Material& material);

}  // namespace clatter::jobs
