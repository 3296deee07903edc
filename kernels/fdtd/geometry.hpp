#pragma once
// Cut-cell description of a rigid body for the finite-volume form of the rigid-body boundary
// condition (docs/fdtd.md): per cell, the fluid volume fraction, the fluid fraction of each face,
// and for each of the six rigid-body fields the normal body flux through the solid parts of its
// faces. A body is given to it as its solid part along axis-aligned lines (SolidBody): the
// ellipsoid x^2/A^2 + y^2/B^2 + z^2/C^2 <= 1 by its analytic chord, a closed triangle mesh by the
// intervals between its sorted crossings (kernels/fdtd/mesh_body.hpp). The volume, face and flux
// formulas are one code path for every body.
#include <array>

namespace clatter::kernels::fdtd {

// The solid part of a segment of an axis-aligned line: its total length and first moment (the
// integral of the coordinate along the line over the solid part).
struct Chord {
  double length = 0, moment = 0;
};

// A cell-sized box against a body: entirely outside, entirely inside, or maybe cut.
enum class BoxClass { outside, inside, maybe_cut };

class SolidBody {
 public:
  virtual ~SolidBody() = default;
  // The solid part of the segment lo <= x[along] <= hi of the line x[axis_p] = p, x[axis_q] = q.
  // (p, q) are given in the caller's order: the ellipsoid evaluates its quadric in that order, so
  // a fixed order keeps its results bit-identical to the analytic code before the generalisation.
  virtual Chord chord(int along, int axis_p, double p, int axis_q, double q, double lo, double hi) const = 0;
  // Conservative: outside/inside only when the whole box [lo, hi] is; maybe_cut otherwise.
  virtual BoxClass classify(const std::array<double, 3>& lo, const std::array<double, 3>& hi) const = 0;
  // The axis-aligned bounding box.
  virtual std::array<double, 3> box_lo_m() const = 0;
  virtual std::array<double, 3> box_hi_m() const = 0;
  // Mirror-symmetric in the three planes x = 0, y = 0, z = 0: cell_geometry then computes every
  // cell from its image in the positive octant, so mirrored cells get exactly mirrored results
  // (octant mode needs this; a full-domain solve of a symmetric body keeps it bit-symmetric).
  virtual bool mirror_symmetric() const = 0;
  // Radius of the smallest origin-centred sphere holding the body.
  virtual double bounding_radius_m() const = 0;
  virtual bool contains(double x, double y, double z) const = 0;
};

struct Ellipsoid final : SolidBody {
  double a_m = 0, b_m = 0, c_m = 0;  // semi-axes along x, y, z
  Ellipsoid() = default;
  Ellipsoid(double a, double b, double c) : a_m(a), b_m(b), c_m(c) {}
  bool contains(double x, double y, double z) const override {
    return x * x / (a_m * a_m) + y * y / (b_m * b_m) + z * z / (c_m * c_m) < 1.0;
  }
  Chord chord(int along, int axis_p, double p, int axis_q, double q, double lo, double hi) const override;
  BoxClass classify(const std::array<double, 3>& lo, const std::array<double, 3>& hi) const override;
  std::array<double, 3> box_lo_m() const override { return {-a_m, -b_m, -c_m}; }
  std::array<double, 3> box_hi_m() const override { return {a_m, b_m, c_m}; }
  bool mirror_symmetric() const override { return true; }
  double bounding_radius_m() const override;
};

// Mirror parity of rigid-body field i (1..6) across the plane normal to `axis` (eqs. 16-21):
// +1 if p_i(mirrored x) = p_i(x), -1 if it changes sign. Field 0 (a monopole) is even everywhere.
int field_parity(int field, int axis);

struct CellGeometry {
  double beta = 1;                      // fluid volume fraction of the cell
  std::array<double, 6> alpha{};        // fluid fraction of faces -x, +x, -y, +y, -z, +z
  std::array<double, 6> body_flux{};    // fields 1..6: (1/dx^2) sum over faces of the integral of
                                        // g_i . n_face over the face's solid part (n outward)
  bool fully_fluid() const;
  bool solid() const;                   // no fluid volume or no open face: never updated
};

// Geometry of the cell centred at `centre_m` (side dx_m), sampled with `samples` points per face
// edge and exact chords along the remaining axis. For a mirror-symmetric body it is computed for
// the mirror image of the cell in the positive octant and mirrored back, so mirrored cells get
// exactly mirrored results.
CellGeometry cell_geometry(const SolidBody& body, const std::array<double, 3>& centre_m, double dx_m, int samples);

}  // namespace clatter::kernels::fdtd
