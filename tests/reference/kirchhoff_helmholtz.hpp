#pragma once
// The transfer's independent far-field check (docs/transfer.md "Validation"): the
// Kirchhoff-Helmholtz integral p(x) = int_S [p(y) dG/dn_y - G(x, y) g(y)] dS_y, G = e^{-ikr} / 4 pi r,
// n out of the body, over the 8 mirror images of an octant grid, with the exterior solution's
// surface pressure and the *prescribed* Neumann data g, so that the fit's boundary error shows.
#include <complex>
#include <functional>
#include <vector>

#include "kernels/transfer/mode_transfer.hpp"

namespace clatter::reference {

// The worst relative difference of |p| between `expansion` and the integral at 10 points of a
// Fibonacci lattice at radius r_m (relative to |p|, or to 1 % of the lattice's largest |p| where
// |p| is smaller: near a mode's nodal plane). g(s): the prescribed g at the grid's points mirrored by s.
double far_field_vs_kirchhoff_helmholtz(const kernels::transfer::Multipole& expansion,
                                        const kernels::transfer::ExteriorSolution& solution,
                                        const kernels::transfer::SurfacePoints& grid,
                                        const std::function<std::vector<double>(int)>& g, double r_m);

// The same for any surface quadrature (points, outward unit normals, weights) with the exterior
// solution's surface pressure p and the prescribed g = dp/dn at its points.
double far_field_vs_kirchhoff_helmholtz(const kernels::transfer::Multipole& expansion,
                                        const std::vector<Eigen::Vector3d>& points_m,
                                        const std::vector<Eigen::Vector3d>& normals,
                                        const std::vector<double>& weights_m2,
                                        const std::vector<std::complex<double>>& pressure,
                                        const std::vector<double>& g, double r_m);

}  // namespace clatter::reference
