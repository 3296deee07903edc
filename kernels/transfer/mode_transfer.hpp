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
#include "model/modal_bank.hpp"

namespace clatter::kernels::transfer {

// The settings are the bank's own (model/modal_bank.hpp): one definition that the modal bank
// header holds and this kernel reads, so nothing is copied between the two.
using TransferSettings = model::TransferSettings;

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

// The first attempt's layout at omega, without a fit: its sources and fit points (whole surface),
// and the work of its fit in units of one complex multiply-add: the QR's fit points x unknowns^2
// and ~50 per Green's function the fill and the check evaluate (green_evaluations): what `plan`
// scales a measured entry's transfer time by.
struct LayoutSize {
  long long sources = 0, fit_points = 0;
  double work = 0;
};
LayoutSize layout_size(const std::array<double, 3>& axes_m, double omega_rad_s, double data_spacing_m,
                       const TransferSettings& settings);

// The modal bank's default of TransferSettings::sources_per_wavelength for these ellipsoid
// layouts (the general-shape method of mesh_transfer.hpp keeps 3): at 2.5 the default bank's
// high-k c modes cost a third (the 0.22:0.69:0.69 entry's top mode 10.2 -> 3.1 s) and its residuals stay
// within 1.2e-2 (docs/transfer.md "Cost").
inline constexpr double kEllipsoidSourcesPerWavelength = 2.5;

// axes: semi-axes a <= b <= c [m]; data_spacing_m: the spacing at which u.n is known (the mesh's).
ModeTransfer solve_mode_transfer(const std::array<double, 3>& axes_m, double omega_rad_s, double data_spacing_m,
                                 const SurfaceDisplacement& u, const TransferSettings& settings);

}  // namespace clatter::kernels::transfer
