#pragma once
// The dispersion part of the FDTD error budget (docs/fdtd.md): how far the grid's phase speed
// moves the pulse psi(t; h) after it has travelled a distance, by direction, predicted from each
// scheme's exact discrete dispersion relation. No field is stepped: this is what a solve logs
// before it starts, and what `plan` and the warnings use.
#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

// Highest frequency of psi(t; h)'s band: where |psi^(f)| first falls to 1e-2 of psi^(0) (-40 dB).
double pulse_band_edge_hz(double h_s);

// Relative L2 error of psi(t - r/c; h), the free-field monopole's waveform, after travelling
// distance_m along `direction` (any length), from the scheme's dispersion relation at this
// Courant number and cell size. Components the grid cannot carry count as lost.
double dispersion_error(Scheme scheme, double courant, double dx_m, double c_m_s, double h_s, double distance_m,
                        const double (&direction)[3]);

// The largest dispersion_error over the axis, face-diagonal and body-diagonal directions (the
// extremes of both schemes' anisotropy).
double worst_dispersion_error(Scheme scheme, double courant, double dx_m, double c_m_s, double h_s, double distance_m);

}  // namespace clatter::kernels::fdtd
