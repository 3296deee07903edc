#pragma once
// An independent evaluation of the ground's sound at a listener, for the ground bank and the ground
// source's accuracy tests (docs/ground.md "The rendered sound against an independent route"). In the
// bank's units (distance 1, c_s = 1, mu = 1, unit impulse, rho0 = 1, M = c_s / c0) both routes
// give Pi(t_hat), the antiderivative of the pressure, so that a box average over [t_a, t_b] is
// (Pi(t_b) - Pi(t_a)) / (t_b - t_a). Neither calls kernels/ground/ground_response: they share with
// the bank only Lamb's closed forms (kernels/ground/lamb.hpp), which tests/unit/test_lamb*.cpp
// check against the Cagniard-de Hoop quadrature.
//
// Route A (regularize first): Pi(t) = (1/pi) int_0^pi dpsi int_0^inf dr r v(r, t - M R) / R, the
// Rayleigh integral of the surface's regularized normal velocity towards the air,
// v = -(1/r^3) d^2/dtau^2 (f_eta/r * S)(tau), in closed form (LambSurface::regularized), by
// adaptive Gauss-Kronrod (GSL) with the fronts as break points. Costly (a closed-form evaluation
// is ~20 us): used overhead, where the psi integral is trivial.
//
// Route B (integrate the step first, by other numerics than the bank's): phi(s), the Rayleigh
// integral of the step displacement, by nested adaptive Gauss-Kronrod (GSL QAGP along each ray with
// the fronts and the listener's foot as break points, QAG over psi), on Gauss-Legendre panels in s
// of at most eta/2 (8 points each) whose edges include every time at which phi is not smooth (the direct sound and
// each front's leaky-wave arrival, min over r of x r + M R), graded geometrically towards them; past
// max(M, x_R) + 2 phi is smooth and taken from its Chebyshev interpolant. Then
// Pi(t) = -int phi(s) f_eta''(t - s) ds by the same panels: no sampling of phi, no interpolation,
// no tail model.
#include <vector>

#include "kernels/ground/lamb.hpp"

namespace clatter::reference {

// Route A at times t (elevation 90 degrees only).
std::vector<double> ground_pi_regularized_overhead(const kernels::ground::LambSurface& ground, double mach, double eta,
                                                   const std::vector<double>& t_hat);

// Route B at times t (ascending), any elevation in (0, 90] degrees.
std::vector<double> ground_pi_step_first(const kernels::ground::LambSurface& ground, double mach, double elevation_rad, double eta,
                                         const std::vector<double>& t_hat);

// phi(s) of route B alone (for checks).
double ground_step_volume(const kernels::ground::LambSurface& ground, double mach, double elevation_rad, double s);

}  // namespace clatter::reference
