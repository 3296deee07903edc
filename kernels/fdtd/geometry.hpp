#pragma once
// Cut-cell description of an axis-aligned ellipsoid x^2/A^2 + y^2/B^2 + z^2/C^2 <= 1 centred on
// the origin, for the finite-volume form of the rigid-body boundary condition (docs/fdtd.md):
// per cell, the fluid volume fraction, the fluid fraction of each face, and for each of the six
// rigid-body fields the normal body flux through the solid parts of its faces.
#include <array>

namespace clatter::kernels::fdtd {

struct Ellipsoid {
  double a_m = 0, b_m = 0, c_m = 0;  // semi-axes along x, y, z
  bool contains(double x, double y, double z) const {
    return x * x / (a_m * a_m) + y * y / (b_m * b_m) + z * z / (c_m * c_m) < 1.0;
  }
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
// edge and analytic extents along the remaining axis. Computed for the mirror image of the cell
// in the positive octant and mirrored back, so mirrored cells get exactly mirrored results.
CellGeometry cell_geometry(const Ellipsoid& body, const std::array<double, 3>& centre_m, double dx_m, int samples);

}  // namespace clatter::kernels::fdtd
