#pragma once
// Rigid-body impacts as continuous acceleration pulses (Chadwick, Zheng & James 2012, section 3):
// Hertz contact gives the duration tau of an impact, and the contact force is the half-sine
// S(t; t0, tau) of eq. (3) scaled so that it delivers the impulse J.
#include <array>
#include <numbers>

#include "model/material.hpp"

namespace clatter::kernels {

// Hertz (Johnson, Contact Mechanics, 1985, section 11.4): two elastic bodies meeting at relative
// normal speed v_n with effective mass m* (1/m* = 1/m1 + 1/m2; the ground: m2 = infinity) and
// effective radius R* (1/R* = 1/R1 + 1/R2; a flat ground: R2 = infinity) stay in contact for
//   tau = 2.868 (m*^2 / (R* E*^2 v_n))^(1/5),   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.
// Only E and nu of the materials enter.
double hertz_contact_time_s(double effective_mass_kg, double effective_radius_m, const model::Material& a,
                            const model::Material& b, double normal_speed_m_s);

// S(t; t0, tau) of eq. (3): sin(pi (t - t0) / tau) on [t0, t0 + tau], else 0.
double half_sine(double t_s, double t0_s, double tau_s);
// The peak force of a half-sine contact delivering impulse J: integral of F_max S = 2 tau F_max / pi.
inline double half_sine_peak(double impulse_n_s, double tau_s) { return std::numbers::pi * impulse_n_s / (2 * tau_s); }

}  // namespace clatter::kernels
