#pragma once
#include <memory>
#include <optional>
#include <string_view>

#include "kernels/fdtd/geometry.hpp"
#include "kernels/fdtd/mesh_body.hpp"
#include "kernels/fdtd/grid.hpp"

namespace clatter::kernels::fdtd {

// The update of the fluid away from the body and the absorbing layer (docs/fdtd.md). Both are
// stable for Courant numbers up to 1/sqrt(3).
enum class Scheme {
  // Standard rectilinear leapfrog: the 7-point Laplacian, second order in space and time.
  srl,
  // Modified-equation scheme, fourth order in space and time: the 13-point fourth-order Laplacian
  // plus (c dt)^2/12 times the square of the 7-point one (25 points).
  me4,
};
const char* scheme_name(Scheme s);
// The scheme named `name` ("me4" or "srl"), or nullopt.
std::optional<Scheme> scheme_from_name(std::string_view name);

// Cells before the PML over which me4 blends into the layer's 7-point update (Operator::blend);
// listeners must lie beyond them. 0 for srl, or without a layer.
inline constexpr int kBlendCells = 8;
inline int blend_cells(Scheme s, int pml_cells) { return s == Scheme::me4 && pml_cells > 0 ? kBlendCells : 0; }

// Everything one FDTD solve needs, in SI units. Built and validated by banks/pan/solve_spec.cpp.
struct Problem {
  Grid grid;
  double c_m_s = 343.2;
  double rho_kg_m3 = 1.2041;
  double dt_s = 0;
  double h_s = 1e-4;             // width of the pulse psi(t; h) driving the source
  int field = 1;                 // 1..6: rigid-body field of `body` (eq. 9); 0: monopole at the origin, no body
  Ellipsoid body;                // the body, unless `mesh` is set
  // A body given as a closed triangle mesh (centred on its centre of mass), shared and immutable:
  // copies of the Problem (one per field and rank) share its bin index. Replaces `body` when set.
  std::shared_ptr<const MeshBody> mesh;
  int cut_cell_samples = 16;     // samples per cell edge for volume and face fractions
  double pml_reflection = 1e-5;  // design normal-incidence reflection of the PML grading
  Scheme scheme = Scheme::me4;

  // The rigid body of fields 1..6: the mesh when there is one, else the ellipsoid.
  const SolidBody& solid() const { return mesh ? static_cast<const SolidBody&>(*mesh) : body; }
  double courant() const { return c_m_s * dt_s / grid.dx_m; }
  // Mirror sign of this field across the plane normal to `axis`.
  int parity(int axis) const { return field_parity(field, axis); }
};

}  // namespace clatter::kernels::fdtd
