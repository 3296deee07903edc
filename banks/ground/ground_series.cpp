#include "banks/ground/ground_series.hpp"

#include "kernels/ground/lamb.hpp"

namespace clatter::jobs {

kernels::ground::VolumeSeries ground_volume(const GroundSpec& spec, std::size_t material, std::size_t elevation) {
  const GroundWindow w = ground_window(spec, material, elevation);
  const kernels::ground::LambSurface surface(spec.materials.at(material).poisson);
  return kernels::ground::step_volume_series(surface, w.mach, spec.elevation_rad.at(elevation), w.s_end, spec.ds, spec.volume);
}

model::GroundSeries ground_series(const GroundSpec& spec, const GroundWindow& w, const kernels::ground::VolumeSeries& volume,
                                  double eta) {
  auto p = kernels::ground::pressure_antiderivative(volume, eta, w.t_hat_start(eta), eta / spec.samples_per_eta, w.t_hat_end(eta));
  return {p.t_hat_start, p.dt_hat, std::move(p.pi), volume.tail.pi_tail()};
}

}  // namespace clatter::jobs
