#pragma once
// A ball dropped on the ground, heard at a distance: the ground's sound against the ball's, the
// setting of Qu & James's relative-intensity tables (seed 004). What "ball sound" means here, and
// every other assumption, is stated in docs/ground.md ("The ball drop"):
//   - the ball: a rigid sphere of radius a and density rho_b, falling from height h, stopped with
//     restitution e by a half-sine contact force of duration t_c (the same t_c for every pair, as
//     004's "the ball sound is unaffected" by the ball's density and the ground's stiffness needs);
//   - the ball's sound: its acceleration noise, the compact rigid sphere's dipole with its near
//     field, doubled by its image in the rigid ground (no modal ringing);
//   - the ground's sound: the impulse J = m (1 + e) v as 004's smoothed delta, eps = c_s t_c / 4,
//     through Lamb's problem and the Rayleigh integral (kernels/ground/ground_response.hpp);
//   - intensity: the energy int p^2 dt of each at the listener, compared in dB.
#include "kernels/ground/ground_response.hpp"

namespace clatter::kernels::ground {

struct BallDrop {
  double ball_radius_m = 0.01, ball_density_kg_m3 = 7850, drop_height_m = 1, restitution = 0;
  // 1 ms: long enough that c_s^2 t_c > 2 D c0 for every ground whose shear waves outrun the air,
  // the regime where 004's columns follow 1/E (docs/ground.md, "The ball drop"); a 1 cm steel ball
  // on steel from 1 m has a Hertz time of 53 us, which puts steel itself near that knee.
  double contact_time_s = 1e-3;
  double distance_m = 1, elevation_rad = 1.5707963267948966;
  double c0_m_s = 343.2, rho0_kg_m3 = 1.2041;
  double impulse_n_s() const;
};

struct DropSound {
  double ground_energy_pa2_s = 0, ball_energy_pa2_s = 0;
  double ground_peak_pa = 0, ball_peak_pa = 0;
  double eta = 0;  // eps / D
  double relative_db() const;  // 10 log10(ground / ball)
};

// The ground's and the ball's sound for one drop on one ground. `ds_per_eta` samples phi at
// eta / ds_per_eta.
DropSound drop_sound(const BallDrop& drop, const model::Material& ground, double ds_per_eta = 8, const VolumeSettings& settings = {});

// The ball's pressure at the listener, t after the first contact (exposed for tests).
double ball_pressure(const BallDrop& drop, double t_s);

}  // namespace clatter::kernels::ground
