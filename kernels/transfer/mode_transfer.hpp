#pragma once
// One mode's acoustic transfer, end to end: Neumann data dp/dn = rho omega^2 u.n from the mode's
// surface shape, the equivalent-source fit (equivalent_sources.hpp) sized by the air wavelength
// and the data's own spacing, its boundary residual on an independent grid, and the multipole
// expansion about the centre (multipole.hpp) truncated where the far field's tail is negligible.
// If the residual misses its target (a source layer near one of its own interior resonances, or
// a field the layer is too deep to resolve), the fit is repeated with other layer depths and the
// best is kept; the attempt count and residual are reported per mode (docs/transfer.md).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <complex>
#include <memory>

#include "kernels/transfer/ellipsoid_points.hpp"
#include "kernels/transfer/equivalent_sources.hpp"
#include "kernels/transfer/multipole.hpp"

namespace clatter::kernels::transfer {

struct TransferSettings {
  double sound_speed_m_s = 343.2;
  double air_density_kg_m3 = 1.2041;
  double points_per_source = 1.5;      // fit points per angle / sources per angle (and >= the data's)
  double sources_per_wavelength = 3;     // source spacing <= lambda / this (and <= the layer depth)
  std::vector<double> source_depths{0.65, 0.5, 0.35};  // layer depth / a, tried in this order
  double residual_target = 1e-2;       // residual x normal_fraction above it tries the next depth
  double class_threshold = 1e-3;       // parity classes below this share of ||g|| are not fitted
  double tail_tolerance = 1e-3;        // far-field L2 share the truncation may drop
  int minimum_per_angle = 6;
  // A ceiling on the sources of one octant (the QR costs their cube): past it both counts shrink
  // alike and the residual says what that cost. The default sphere entry's top mode needs ~580.
  int max_sources_per_octant = 900;
};

// The displacement u [m per unit modal amplitude] at the points of the first octant's mirror s.
using SurfaceDisplacement = std::function<std::vector<Eigen::Vector3d>(const SurfacePoints& octant, int s)>;

// A mode given at the nodes of a curved surface mesh of the ellipsoid (shape: [node][3]),
// through SurfaceInterpolator. The spans are not copied: they must outlive the function.
SurfaceDisplacement mesh_displacement(const std::array<double, 3>& axes_m,
                                            std::span<const std::array<double, 3>> nodes_m,
                                            std::span<const std::array<std::int32_t, 6>> faces,
                                            std::span<const double> shape);

// The fitted field itself (sources and strengths), for checks against the expansion: valid
// anywhere outside the source layer, the surface included (class_fields, field_at_mirror).
struct ExteriorSolution {
  double k_rad_m = 0;
  SourceLayout layout;
  SourceFit fit;
};

struct ModeTransfer {
  Multipole expansion;
  std::shared_ptr<const ExteriorSolution> solution;
  double boundary_residual = 0;  // ||dp/dn - g|| / ||g|| on the check grid (L2 over the surface)
  double normal_fraction = 0;    // ||u.n|| / ||u||: near 0 for a mode that slides along its surface
                                 // (a sphere's torsional modes), whose g is the mesh's noise
  double amplification = 0;      // largest ||A|| ||c|| / ||b|| of the fitted classes
  double source_depth = 0;       // layer depth / a of the kept attempt
  int attempts = 0, classes = 0;
  int sources = 0, fit_points = 0;  // whole surface (8 octants)
};

// axes: semi-axes a <= b <= c [m]; data_spacing_m: the spacing at which u.n is known (the mesh's).
ModeTransfer solve_mode_transfer(const std::array<double, 3>& axes_m, double omega_rad_s, double data_spacing_m,
                                 const SurfaceDisplacement& u, const TransferSettings& settings);

}  // namespace clatter::kernels::transfer
