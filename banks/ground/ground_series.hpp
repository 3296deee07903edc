#pragma once
// One row of the ground bank computed serially: the volume series of a (material, elevation) and
// each eta's series of Pi with its tail, at the spec's sampling. build_ground_row (ground_job.cpp)
// runs it under the sweep; tests build in-memory banks with it, exactly as clatter-bank does.
#include "banks/ground/ground_spec.hpp"
#include "kernels/ground/ground_response.hpp"
#include "model/ground_bank.hpp"

namespace clatter::jobs {

// phi from the window's first arrival to s_end at the spec's ds, and its tail.
kernels::ground::VolumeSeries ground_volume(const GroundSpec& spec, std::size_t material, std::size_t elevation);

// Pi on the window [first arrival - 20 eta, s_end + 20 eta] at eta / samples_per_eta, and the tail
// that continues it (model/ground_bank.hpp).
model::GroundSeries ground_series(const GroundSpec& spec, const GroundWindow& window, const kernels::ground::VolumeSeries& volume,
                                  double eta);

}  // namespace clatter::jobs
