#pragma once
// One mode's acoustic transfer for any closed body given by its curved surface mesh (6-node
// triangles: 3 corners counter-clockwise seen from outside, then the mid-nodes of edges 01, 12,
// 20, as model::ModalEntry stores them): the exterior Neumann problem dp/dn = rho omega^2 u.n
// (e^{+i omega t}) by equivalent sources on an inner offset of the surface, then the multipole
// expansion about the origin (the caller puts it at the centre of mass). The ellipsoid's solver
// (mode_transfer.hpp) uses its mirror planes; this one uses no symmetry. The layout:
//  - the depth of a source follows the largest ball inside the body that touches the surface at
//    its foot point (radius D: the local half-thickness or the concave curvature radius, whichever
//    is smaller): depth f D for the tried factors f of settings.source_depths;
//  - where the body is too thin for two layers a source spacing apart (a plate), one layer on the
//    mid-surface (depth D) of monopoles *and* normal dipoles: monopoles there are even across the
//    plate and cannot make a bending mode's odd field;
//  - spacing from the air wavelength, the data's node spacing and the depth, under a ceiling on
//    the unknowns (the QR costs their square times the fit points).
// Accurate for bulky and smooth bodies; sharp rims and thin plates are fitted with large
// residuals at an affordable cost (measured in the docs): boundary_residual says so per mode.
// docs/transfer.md "Any closed mesh (object bank)" derives and measures it.
#include <Eigen/Core>
#include <array>
#include <complex>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "kernels/transfer/multipole.hpp"
#include "model/modal_bank.hpp"

namespace clatter::kernels::transfer {

// The fitted sources: valid anywhere outside them (the surface included).
struct MeshSources {
  double k_rad_m = 0;
  std::vector<Eigen::Vector3d> position_m;
  std::vector<Eigen::Vector3d> dipole_axis;            // unit; zero where the source is a monopole only
  std::vector<std::complex<double>> monopole, dipole;  // strengths: p = q G + d (axis . grad_y) G
  std::vector<double> spread_m;  // > 0: the source is spread over a disk across its axis (mesh_transfer.cpp)

  struct Field {
    std::complex<double> pressure, normal_derivative;
  };
  // p and dp/dn (along the unit `normal`) at x.
  Field field(const Eigen::Vector3d& x_m, const Eigen::Vector3d& normal) const;
};

// A point of the curved surface with its quadrature weight.
struct MeshSurfacePoints {
  std::vector<Eigen::Vector3d> position_m, normal;  // normal: outward, unit
  std::vector<double> weight_m2;
  std::vector<Eigen::Vector3d> displacement_m;       // u interpolated by the face's shape functions
  std::size_t size() const { return position_m.size(); }
};

// Points of every face by an n x n split of its parameter triangle and a 3-point (degree 2) rule
// on each part, n from `spacing_m` and the face's size; u interpolated from `shape` ([node][3],
// may be empty). For quadratures over the surface (the tests' Kirchhoff-Helmholtz integrals).
MeshSurfacePoints mesh_surface_points(std::span<const std::array<double, 3>> nodes_m,
                                      std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shape,
                                      double spacing_m);

struct MeshTransfer {
  Multipole expansion;                           // about the origin
  std::shared_ptr<const MeshSources> solution;   // the fitted field itself, for checks
  double boundary_residual = 0;  // ||dp/dn - g|| / ||g|| on the independent check points (L2 over the surface)
  double normal_fraction = 0;    // ||u.n|| / ||u|| over the surface
  double amplification = 0;      // ||A|| ||c|| / ||b||: the fit's effective condition number
  double source_depth_m = 0;     // the median source depth below its foot point, kept attempt
  double source_spacing_m = 0;   // the largest spacing the layout allowed (after the ceiling)
  int sources = 0;               // source positions; unknowns = sources + dipoles
  int dipoles = 0;
  int fit_points = 0;             // rows of the least squares: area-averaged cells of the surface
  int check_points = 0, attempts = 0;
};

// The kernel's own constants (not stored in a bank).
struct MeshTransferOptions {
  // The QR costs ~16 fit_points x unknowns^2 flops; past this the spacing grows until it fits
  // (the residual then says what that cost); docs/transfer.md has the plate's costs.
  int max_unknowns = 1500;
  double fit_points_per_unknown = 2.0;  // fit cells per unknown at least (the least squares' overdetermination)
};

// nodes_m, faces: the closed surface; shape: the mode's displacement at the nodes, [node][3],
// in m per unit modal amplitude; omega: the mode's angular frequency.
MeshTransfer solve_mesh_mode_transfer(std::span<const std::array<double, 3>> nodes_m,
                                      std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shape,
                                      double omega_rad_s, const model::TransferSettings& settings,
                                      const MeshTransferOptions& options = {});

}  // namespace clatter::kernels::transfer
