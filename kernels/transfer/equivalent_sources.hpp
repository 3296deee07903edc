#pragma once
// The exterior Neumann problem of one mode by equivalent sources (Ochmann's source simulation,
// the method of fundamental solutions): monopoles e^{-ikr} / (4 pi r) on a layer inside the surface,
// strengths fitted in weighted least squares to dp/dn = g on a surface quadrature grid. The
// ellipsoid's three mirror planes split g into 8 parity classes; each class is fitted on the first
// octant with mirrored sources (a problem 8x smaller, 512x cheaper to factor), and classes with no
// data are skipped. docs/transfer.md derives and measures it.
#include <Eigen/Core>
#include <array>
#include <complex>
#include <vector>

#include "kernels/transfer/ellipsoid_points.hpp"

namespace clatter::kernels::transfer {

// A point of a spread source (below): its position and its share of the unknowns whose B-splines
// cover it. A tap may be a ghost: the mirror image of an unknown's B-spline across
// the mirror plane `plane` (bit 4: z = 0, bit 2: y = 0; 0: the unknown's own), which a class odd
// across that plane takes with the opposite sign, so the density is smooth across the plane and,
// for an odd class, 0 on it.
struct SpreadTap {
  int unknown = -1;
  double weight = 0;
  int plane = 0;
};
struct SpreadPoint {
  Eigen::Vector3d position_m;
  std::vector<SpreadTap> taps;
  double weight_for(std::size_t tap, int sigma) const {
    return (taps[tap].plane & sigma) ? -taps[tap].weight : taps[tap].weight;
  }
};

// One row of samples of the spread sources, at levels of spacing: levels[0], a midpoint per cell
// within the row's depth (the field's definition: the residual, the field and the expansion use
// it); each next level has cells about 4x larger, two Gauss-Legendre points each, down to one cell
// per panel (the stretch one coarsest cell stands for; level l has size / panels samples per
// panel, in order). A cell of size s seen from distance D through its two points is off by
// ~(s / D)^4 / 4320 of its share (a midpoint's (s / D)^2 / 24, the cell's quadrupole, read the
// residual 10-15 % low), so a point at least kLevelDistance s from a panel may see it at that level.
struct SpreadRow {
  std::vector<std::vector<SpreadPoint>> levels;
  std::vector<double> spacing_m;  // largest gap between neighbouring cells, per level
  std::size_t panels = 1;         // the coarsest level's cells; level l has levels[l].size() / panels samples per panel
};
inline constexpr double kLevelDistance = 2.0;

struct SourceLayout {
  SurfacePoints sources;  // first octant, one per unknown (inner_layer, or a spread source's node); positions only matter
  // Empty: unknown j is a monopole at sources[j]. Else unknown j is a surface density on the
  // source layer (a B-spline about its node, mode_transfer.cpp), sampled by rows of points closer
  // together than their depth, so that its field is smooth on the surface (docs/transfer.md).
  std::vector<SpreadRow> spread;
};

// g on the fit grid: [mirror s][point i] of the octant grid's mirror images.
using MirroredData = std::array<std::vector<double>, 8>;

struct ParityFit {
  int sigma = 0;                               // parity class (bit set: odd in x, y, z)
  Eigen::VectorXcd strengths;                  // per octant source; source j's mirror s has sign parity_sign(s, sigma)
  double data_norm = 0;                        // ||g_sigma||, weighted
  double amplification = 0;                    // ||A|| ||c|| / ||b||: the effective condition number
};

struct SourceFit {
  std::vector<ParityFit> classes;  // the fitted classes only
  double data_norm = 0;            // ||g|| over the whole surface
  double left_out_share = 0;       // ||g|| of the classes not fitted / ||g||
};

// min ||A c - b||^2 + mu^2 ||c||^2, mu = 1e-10 ||A||_F / sqrt(columns), by LAPACK's QR least
// squares (zgels) of [A; mu I]: overlapping sources make A numerically rank-deficient by design,
// and mu keeps c bounded without touching the fit. Serial, so the same on any rank.
Eigen::VectorXcd solve_regularized_least_squares(const Eigen::MatrixXcd& a, const Eigen::VectorXcd& b);

// Fits the parity classes of `g` but the smallest ones that together carry at most `class_budget`
// of ||g|| (on a mesh that is not mirror-symmetric, a mode of one class has all eight, the seven
// others at its discretization error, ~1e-3 each).
SourceFit fit_sources(double k_rad_m, const SurfacePoints& fit, const MirroredData& g, const SourceLayout& layout,
                      double class_budget);

// p and dp/dn of each fitted class on the first-octant points; at mirror s the field is
// sum over classes of parity_sign(s, sigma) times these (a field of class sigma is that sign
// times itself at the mirror image, normals mirrored too).
struct ClassField {
  int sigma = 0;
  std::vector<std::complex<double>> pressure, normal_derivative;
};
// kNormalDerivative leaves the pressures 0: the boundary residual needs dp/dn alone.
enum class FieldParts { kPressureAndNormalDerivative, kNormalDerivative };
std::vector<ClassField> class_fields(double k_rad_m, const SourceFit& fit, const SourceLayout& layout,
                                     const SurfacePoints& points,
                                     FieldParts parts = FieldParts::kPressureAndNormalDerivative);

// Monopoles (octant positions, per fitted class the strength of each) equivalent to the fit: the
// sources themselves, or the points of spread sources with their unknowns' shares summed.
struct ClassMonopoles {
  std::vector<Eigen::Vector3d> position_m;
  std::vector<Eigen::VectorXcd> strengths;  // [fitted class][point]
};
ClassMonopoles class_monopoles(const SourceFit& fit, const SourceLayout& layout);

// The Green's functions (each over its 8 images) that fit_sources evaluates on `fit` and
// class_fields on `check`: points x sources, or for spread sources the samples each point sees at
// its panels' levels. What a fit costs besides its QR.
double green_evaluations(double k_rad_m, const SourceLayout& layout, const SurfacePoints& fit, const SurfacePoints& check);

// The whole field at the points of mirror s.
void field_at_mirror(const std::vector<ClassField>& fields, int s, std::vector<std::complex<double>>& pressure,
                     std::vector<std::complex<double>>& normal_derivative);

}  // namespace clatter::kernels::transfer
