#pragma once
// Adaptive sampling of the modal soundbank's ellipsoid patch (paper §5.2-5.3, Fig. 8): semi-axes
// a <= b <= c with a^2 + b^2 + c^2 = 1 m^2 (scale removed by eq. 11), from the sphere to a thin
// pancake (a/c = min_ratio, b = c) and a thin cigar (b/c = cigar_ratio, a = b).
//
// Coordinates. The patch is parameterized by the log ratios u = ln(b/c) <= 0, v = ln(a/b) <= 0: it
// is the triangle with corners sphere (0, 0), cigar (ln r_c, 0) and pancake (0, ln r) (r =
// min_ratio, r_c = cigar_ratio), u / ln r_c + v / ln r <= 1. With r_c = r that is a/c >= r. The
// two corners are separate because debris is flat (003 Fig. 9): fracture makes plates far thinner
// than it makes needles (docs/modal.md "Sampling the patch" measures both), and a needle is the
// harder entry to mesh. Why logs: the frequencies of plates and rods are powers of the axis
// ratios (a thin plate's bending frequency goes as thickness / width^2, a rod's as thickness /
// length^2), so ln f is close to linear in (u, v) and a relative frequency change, exp(|d ln f|) - 1,
// is near-uniform over the plane: one edge length fits the whole patch for a pure power law, and
// the adaptive refinement only has to handle what the power laws miss (the transitions between the
// sphere, plate and rod regimes, mode crossings), which cluster toward the pancake and cigar corners.
//
// Refinement criterion. An edge of the triangulation whose endpoints' features differ by more than
// `tolerance` (relative_change below) is split at its midpoint in the (u, v) plane. The level-0
// grid cuts the patch triangle into initial_divisions^2 right isosceles triangles (in (u, v)); each
// level then marks the edges over tolerance and refines by newest-vertex bisection (NVB): every
// triangle's refinement edge is the one opposite its newest vertex (at level 0 the hypotenuse), a
// triangle with a marked edge gets its refinement edge marked too (repeated to a fixed point, the
// conforming closure), and each triangle is bisected on its refinement edge if marked, then each
// child on its own (an edge of the parent) if marked: every marked edge is split once per level,
// on both sides, so the mesh stays conforming with no hanging node. NVB here only ever produces two
// shapes (right isosceles triangles with axis-aligned or diagonal legs), so quality never degrades,
// and two levels of bisection halve the legs: after k levels every vertex lies on the grid refined
// 2^k times. Levels stop when no edge is over tolerance or after max_level levels.
//
// Samples are keyed by their integer lattice coordinates on the initial grid refined 2^max_level
// times, so a midpoint shared by two triangles is one sample and no point is ever created twice.
// Everything is deterministic: ordered containers only, new samples in the order of their edges.
#include <array>
#include <functional>
#include <string>
#include <vector>

namespace clatter::kernels::modal {

using Axes = std::array<double, 3>;  // semi-axes a <= b <= c, a^2 + b^2 + c^2 = 1 (metres)

// The patch point with u = ln(b/c), v = ln(a/b) (both <= 0; std::invalid_argument otherwise).
Axes axes_from_log_ratios(double u, double v);
// {ln(b/c), ln(a/b)} of positive axes (std::invalid_argument otherwise).
std::array<double, 2> log_ratios(const Axes& axes);

// The patch's two thin corners (the header's triangle).
struct PatchCorners {
  double min_ratio = 0.1;    // a/c of the pancake corner (b = c): the smallest a/c of the patch, in (0, 1)
  double cigar_ratio = 0.1;  // b/c (= a/c) of the cigar corner (a = b), in [min_ratio, 1)
};
// Why the corners do not make a patch, empty if they do.
std::string corners_violation(const PatchCorners& corners);

// Why `axes` is not a patch point, empty if it is: an axis not finite or not positive; not
// ascending (beyond a relative `tolerance`); off the unit sphere (|a^2 + b^2 + c^2 - 1| >
// tolerance); a/c below min_ratio, or beyond the edge from the cigar to the pancake corner (by more
// than a relative `tolerance`). std::invalid_argument if the corners are not a patch.
std::string patch_violation(const Axes& axes, const PatchCorners& corners, double tolerance = 1e-9);

struct PatchSamplingSettings {
  PatchCorners corners;
  int initial_divisions = 2;   // the log-ratio triangle cut into n^2 triangles at level 0
  double tolerance = 0.1;      // largest allowed relative change of a feature along an edge
  int max_level = 4;           // refinement levels beyond the initial grid (0..16)
};

// Features of a batch of ellipsoids (e.g. their first few normalized natural frequencies), one
// vector per ellipsoid, all the same length, positive. Called once per level with the new points
// only, so the caller can evaluate them in parallel.
using FeatureBatch = std::function<std::vector<std::vector<double>>(const std::vector<Axes>&)>;

struct PatchSampling {
  std::vector<Axes> samples;                  // deterministic order: by level, then by creation
  std::vector<std::vector<double>> features;  // per sample
  std::vector<int> level;                     // per sample: 0 initial, k refined at level k
  std::vector<std::array<int, 3>> triangles;  // the final conforming triangulation, indices into
                                              // samples, counter-clockwise in (u, v)
  double worst_change = 0;                    // largest relative feature change over the final edges
  int edges_over_tolerance = 0;               // final edges still above tolerance (only at max_level)
};

// The adaptive sampling above. std::invalid_argument on bad settings; std::runtime_error when
// `features` returns the wrong number of vectors, vectors of differing or zero length, or a value
// that is not finite and positive.
PatchSampling sample_patch(const PatchSamplingSettings& settings, const FeatureBatch& features);

// The relative change between two feature vectors: max_k |f_k - g_k| / min(f_k, g_k) (same
// lengths, positive entries; std::invalid_argument on a length mismatch).
double relative_change(const std::vector<double>& f, const std::vector<double>& g);

}  // namespace clatter::kernels::modal
