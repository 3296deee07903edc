#pragma once
// The modal soundbank (003 §5, Appendix E) as plain data: the one definition that io/ reads and
// writes (format "clatter-modal-bank", docs/bank-format.md), banks/modal/ builds and the
// synthesizer renders from. Per normalized ellipsoid (a <= b <= c, a^2 + b^2 + c^2 = 1 m^2) of one
// material: every free vibration mode in [f_1, f_max], with its mass-normalized shape on the surface.
// Numbers and vectors only; std only.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/material.hpp"
#include "model/sweep_status.hpp"

namespace clatter::model {

// The quality of the tetrahedral mesh an entry was solved on (kernels/fem/mesh_quality.hpp).
struct ModalMeshStats {
  std::int64_t elements = 0, nodes = 0, dofs = 0;
  double edge_length_m = 0;  // target h inside; the surface spacing follows the curvature
  double max_radius_edge = 0, mean_radius_edge = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  double min_jacobian_ratio = 0;
};

// How the eigen-solve of an entry was set up and what its count check saw.
struct ModalSolveRecord {
  double lambda_lo = 0, lambda_hi = 0;     // the sliced interval of omega^2 [rad^2/s^2]
  std::int64_t below_lo = 0, below_hi = 0; // eigenvalues below each end, by inertia (below_lo: the 6 rigid motions)
  std::int64_t found_in_interval = 0;      // modes the solve returned in [lambda_lo, lambda_hi] (= below_hi -
                                           // below_lo); the entry keeps those from f_1 to f_max
  std::int64_t shifts = 0;                 // shifts factorised
  double first_mode_estimate_hz = 0;       // f_1 from the coarse pre-solve that set h and the interval
  std::string solver_options;              // the PETSc/SLEPc options of the solve
};

// What an entry's band guarantees (docs/modal.md "The band and what it guarantees"). Conforming
// FEM frequencies lie above the exact ones (Rayleigh-Ritz), by at most mesh_error (relative) up to
// f_max on this mesh; so with every discrete mode up to keep_to_hz stored, every mode whose exact
// frequency is at most f_max_hz is stored.
struct ModalBand {
  double f_max_hz = 0;    // f_max_multiple x f_1 (the entry's own f_1)
  double mesh_error = 0;  // the margin: bound on the relative frequency error of the mesh at f_max
  double keep_to_hz = 0;  // f_max (1 + mesh_error); the multiplet straddling it is kept whole
};

// The symmetry that decides an entry's multiplets (kernels/modal/multiplets.hpp) and how cleanly
// the mode shapes showed it.
struct ModalSymmetry {
  std::string kind = "none";     // "sphere", "spheroid" or "none" (triaxial, or an object's mesh)
  std::int32_t axis = -1;        // a spheroid's axis of revolution (0 x, 1 y, 2 z); -1 otherwise
  double order_defect = 0;       // largest distance of a computed |m| or n from its integer
  std::int32_t incomplete = 0;   // multiplets with fewer members than the symmetry demands
};

// Wall times and memory of an entry: provenance of one run, left out of the content hash.
struct ModalEntryCost {
  double mesh_s = 0, assembly_s = 0, estimate_s = 0, solve_s = 0, total_s = 0;  // solve_s: basis rule included
  double transfer_s = 0;        // the acoustic transfer of every mode (wall time of the group)
  double transfer_core_s = 0;   // the same summed over the group's ranks
  double factor_memory_mb = 0;  // MUMPS' INFOG(21) (10^6 bytes), largest rank, count-check factorisation
  double memory_max_mb = 0;     // resident memory after the solve, largest rank (10^6 bytes)
  std::int32_t ranks = 0;
};

// Every mode's acoustic transfer (docs/transfer.md): the complex pressure per unit modal amplitude
// outside the proxy, p(x) = sum_{n <= order} sum_m M_n^m h_n^(2)(k r) Y_n^m(theta, phi) about the
// centre (003 eqs. 6-7; e^{+i omega t}, orthonormal Y_n^m with the Condon-Shortley phase), from
// the exterior Neumann problem dp/dn = rho_air omega^2 u.n. Valid for r >= 2c.
struct ModalTransfer {
  std::vector<double> wavenumber_rad_m;   // k = omega / c_air per mode
  std::vector<std::int32_t> order;        // n-bar per mode
  std::vector<double> coefficients;       // M_n^m [Pa] as (re, im), mode after mode, (order + 1)^2 each,
                                          // at index n^2 + n + m
  std::vector<double> boundary_residual;  // ||dp/dn - g|| / ||g|| on the check grid
  std::vector<double> normal_fraction;    // ||u.n|| / ||u|| over the surface: near 0 for a mode that slides
                                          // along it (torsion), whose g and residual are the mesh's noise
  std::vector<double> amplification;      // ||A|| ||c|| / ||b||: the fit's effective condition number
  std::vector<double> source_depth;       // depth of the source layer kept, / a
  std::vector<std::int32_t> attempts;     // source layers tried (1: the first met the residual target)
  std::vector<std::int32_t> sources;      // equivalent sources of the kept fit (whole surface)

  // Index of mode i's first (re, im) pair in `coefficients`.
  std::size_t offset(std::size_t mode) const {
    std::size_t at = 0;
    for (std::size_t i = 0; i < mode; ++i) at += static_cast<std::size_t>((order[i] + 1) * (order[i] + 1));
    return at;
  }
};

struct ModalEntry {
  std::uint32_t sample = 0;                // index in the config's patch.samples (task eNNN)
  std::array<double, 3> axes_m{};          // semi-axes a <= b <= c, a^2 + b^2 + c^2 = 1
  std::vector<double> frequencies_hz;      // ascending, f_1 .. f_max
  std::vector<double> damping_ratios;      // the bank material's Rayleigh damping at each frequency
  std::vector<std::int32_t> cluster;       // per mode: its cluster (neighbours within the cluster gap), 0-based
  std::vector<std::int32_t> multiplet;     // per mode: its multiplet, degenerate by symmetry, 0-based, numbered
                                           // in the order of their lowest members
  std::vector<std::int32_t> symmetry_order;  // per mode: |m| about a spheroid's axis, degree n on a sphere, -1
  std::vector<double> relative_residuals;  // ||K u - lambda M u|| / ||K u||
  // The curved surface: nodes and 6-node triangles (vertices counter-clockwise from outside,
  // then the mid-nodes of edges 01, 12, 20).
  std::vector<std::array<double, 3>> surface_nodes_m;
  std::vector<std::array<std::int32_t, 6>> surface_faces;
  // [mode][surface node][3]: mass-normalized displacement (u^T M u = 1) [kg^-1/2], the sign and
  // basis rule of kernels/modal/mode_basis.hpp applied.
  std::vector<double> shapes;
  ModalTransfer transfer;
  ModalMeshStats mesh;
  ModalSolveRecord solve;
  ModalBand band;
  ModalSymmetry symmetry;
  ModalEntryCost cost;

  std::size_t modes() const { return frequencies_hz.size(); }
};

// The transfer's promise per mode (docs/transfer.md): a boundary residual within
// kResidualPromised wherever the mode's normal fraction exceeds kNormalFractionPromised (below
// it the data u.n is mostly the mesh's noise: a torsional mode). The bank warns per entry and
// `info` prints the worst such residual.
inline constexpr double kResidualPromised = 0.02;
inline constexpr double kNormalFractionPromised = 0.3;

// How each mode's acoustic transfer is computed (kernels/transfer/mode_transfer.hpp, which takes
// this struct as is). The bank file holds `method` and the six settings a config may change
// (/settings/transfer); the kernel's own constants below them keep their defaults when read back.
struct TransferSettings {
  std::string method;                    // recorded in the bank, not read by the kernel: e.g. "equivalent
                                         // sources, 8 parity classes; multipole about the centre"
  double sound_speed_m_s = 343.2;
  double air_density_kg_m3 = 1.2041;
  double points_per_source = 1.5;        // fit points per angle / sources per angle (and >= the data's)
  double sources_per_wavelength = 3;     // source spacing <= lambda / this (and <= the layer depth)
  double residual_target = 1e-2;         // residual x normal_fraction above it tries the layer's next depth
  double tail_tolerance = 1e-3;          // far-field L2 share the truncation may drop
  // The kernel's constants, not stored in the bank.
  std::vector<double> source_depths{0.65, 0.5, 0.35};  // layer depth / a, tried in this order
  // The parity classes left unfitted (the smallest first) carry together at most this share of
  // ||g||: on a TetGen mesh, which is not mirror-symmetric, a mode of one class has all eight,
  // the seven others at its discretization error (1e-3 - 5e-3 of ||g|| on the default bank's
  // 0.35:0.56:0.75 entry), and fitting them cost up to 8x the one class. Half residual_target,
  // so it adds at most 12 % to a residual at the target; where a mode misses the bank's promise
  // with classes left out, it is fitted again with all but 1e-3 of ||g|| (mode_transfer.cpp).
  double class_budget = 5e-3;
  int minimum_per_angle = 6;
  // A ceiling on the sources of one octant (the QR costs their cube): past it both counts shrink
  // alike and the residual says what that cost. The default sphere entry's top mode needs ~580.
  int max_sources_per_octant = 900;
  // Flat bodies (b >= rim_aspect a): the rim-graded layout instead (docs/transfer.md "Flat
  // bodies"): spread sources on the confocal ellipsoid of thin semi-axis rim_inner_fraction a,
  // neighbours within rim_spacing_per_depth of their depth; a second attempt 1.2x denser in the
  // air wavelength where the first misses kResidualPromised (not residual_target: mode_transfer.cpp).
  double rim_aspect = 2;
  // ...and bodies thin against their length (a <= rim_thin_ratio c: a needle, a splinter), whose
  // tips the layer resolves as badly as a rim: measured on the default bank's 0.08-0.14 : 0.11-0.23
  // : 0.97-0.99 entries, residuals 5-20x lower and the fits 1-3.6x faster; at a / c = 0.18 the rim
  // layout is 5x slower (docs/transfer.md "Needles and splinters").
  double rim_thin_ratio = 0.15;
  double rim_inner_fraction = 0.3;
  double rim_spacing_per_depth = 0.7;
};

// How the eigen-solve of every entry is set up (banks/modal/modal_solve.hpp), and the pre-solve
// that estimates f_1 with it. The bank file holds the first five (/settings); max_iterations and
// nev_per_shift change the work, not the result, so they are not stored and read back as 0.
struct ModalSolveSettings {
  double f_max_multiple = 4;             // f_max = f_max_multiple * f_1 (a bank: the smallest; BandRule)
  double cluster_gap = 5e-3;             // relative frequency gap that separates clusters (each holds whole
                                         // multiplets: their mesh split is smaller)
  double degenerate_gap = 1e-8;          // Ritz values closer than this get the reference-field basis
                                         // (splits far below any mesh asymmetry)
  double tolerance = 1e-11;              // SLEPc's -eps_tol
  double residual_limit = 1e-8;          // every mode's relative residual is at most this
  std::int64_t max_iterations = 0;       // SLEPc restarts per shift (-eps_max_it); 0: SLEPc's default
  std::int64_t nev_per_shift = 0;        // eigenpairs sought around each shift; 0: SLEPc's default
};

// How each entry's band is chosen (docs/modal.md "Every audible mode"): [f_1, k f_1] with
//   k = min(top_hz * largest_piece_m / (2 c f_1), top_hz / proxy_above_hz),
// clamped to [solve.f_max_multiple, max_multiple], c the entry's normalized longest semi-axis.
// Equi-frequency scaling gives a piece of the entry's shape and longest dimension L the base
// frequency f_0 = f_1 2c / L, so every piece up to largest_piece_m gets every mode up to top_hz;
// and a piece whose f_0 is below proxy_above_hz rings with its own model (003 section 5.4), so no
// proxy needs more than top_hz / proxy_above_hz. largest_piece_m = 0: k = solve.f_max_multiple;
// proxy_above_hz = 0: no such bound.
struct BandRule {
  double top_hz = 20000;          // the top of the audible band
  double largest_piece_m = 0;     // the longest piece (2c) that gets every mode to top_hz
  double proxy_above_hz = 0;      // pieces with a lower f_0 ring with their own models, not a proxy
  double max_multiple = 64;       // the cost's limit on k
};

// k of an entry whose normalized longest semi-axis is c_m and first frequency f1_hz.
inline double band_multiple(const BandRule& band, double min_multiple, double c_m, double f1_hz) {
  double wanted = band.top_hz * band.largest_piece_m / (2 * c_m * f1_hz);
  if (band.proxy_above_hz > 0) wanted = std::min(wanted, band.top_hz / band.proxy_above_hz);
  return std::max(min_multiple, std::min(band.max_multiple, wanted));
}

// What every entry of a bank shares: the material and the settings that decide its content.
struct ModalBankHeader {
  Material material;
  ModalSolveSettings solve;              // solve.f_max_multiple: the smallest k of any entry
  BandRule band;
  double elements_per_wavelength = 0;  // h = shear wavelength at f_max / this
  double min_ratio = 0;                // smallest a/c of the sampled patch (its pancake corner, b = c)
  double cigar_ratio = 0;              // b/c of its cigar corner (a = b): kernels/modal/patch_sampling.hpp
  double coarse_edge_m = 0;            // h of the pre-solve that estimates f_1
  double elements_through_thickness = 0;         // h <= 2 a / this (a the smallest semi-axis), fine mesh
  double coarse_elements_through_thickness = 0;  // the same cap on the pre-solve's mesh
  // Entries whose a / b is below this are meshed in layers (kernels/fem mesh_layered_ellipsoid,
  // in-plane h from the bending wavelength): `layers` through the thickness, `coarse_layers` on
  // the pre-solve's mesh; 0: none.
  double layered_below_ratio = 0;
  std::int32_t layers = 2, coarse_layers = 1;
  std::int32_t ranks_per_task = 0;     // ranks that solved each entry (shapes agree across it to ~1e-8)
  std::string solver_libraries;        // e.g. "PETSc 3.18.5, SLEPc 3.18.2": the last bits depend on them
  TransferSettings transfer;
};

struct ModalBank {
  ModalBankHeader header;
  std::vector<ModalEntry> entries;     // in the order of the config's samples; failed ones absent (/sweep)
  SweepStatus sweep;
};

}  // namespace clatter::model
