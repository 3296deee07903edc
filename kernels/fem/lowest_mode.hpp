#pragma once
// The lowest elastic (non-rigid) free-vibration frequency of the uniform solid bounded by a closed
// triangle mesh: the synthesizer's equi-frequency scaling needs omega_0 of a debris piece given as
// an OBJ mesh, cheaply (a few hundred triangles: ~0.2 s; 1280: ~2 s) and to a few percent.
//
// The solid is filled by TetGen and discretized with straight 10-node tetrahedra (coarse is
// enough: quadratic elements resolve the lowest bending and torsion modes with a few elements
// across). The eigenproblem K u = lambda M u, free boundary, is solved without PETSc, the six
// rigid motions M-orthogonally deflated: block Lanczos on the shift-inverted linear (vertex)
// subspace gives a start, LOBPCG with a two-level preconditioner finishes on the quadratic space
// (lowest_mode.cpp explains why not a direct solve).
#include <array>
#include <cstdint>
#include <vector>

#include "kernels/fem/assembly.hpp"
#include "kernels/fem/tetgen_fill.hpp"

namespace clatter::kernels::fem {

struct LowestModeSettings {
  double edge_length_m = 0;  // target tetrahedron edge; 0: (volume)^(1/3) / 2
  // Converged when the two lowest Ritz values change by less than this (relative) in an
  // iteration and their relative residuals are below its square root (a Ritz value's error is
  // quadratic in the residual).
  double tolerance = 1e-8;
  int max_iterations = 200;  // LOBPCG iterations
  int block_size = 6;        // one more than a 5-fold multiplet (a sphere's T2), to see it whole
};

struct LowestMode {
  double frequency_hz = 0;         // lowest non-rigid mode
  double second_frequency_hz = 0;  // the next Ritz value (to see multiplets); 0 if not computed
  std::int64_t elements = 0, nodes = 0, dofs = 0;
  int iterations = 0;              // LOBPCG iterations taken
  double relative_residual = 0;    // ||K u - lambda M u|| / ||K u|| of the lowest pair
  double volume_m3 = 0;            // of the tetrahedralized solid
};

// Throws std::invalid_argument with a clear message for a mesh TetGen cannot fill (open,
// non-manifold, inconsistently oriented, self-intersecting, degenerate), E <= 0, nu not in
// (-1, 0.5), rho <= 0; std::runtime_error if the eigen-iteration does not reach the tolerance.
// Deterministic: the same input gives the same result bit for bit.
LowestMode lowest_free_mode(const std::vector<std::array<double, 3>>& vertices_m,
                            const std::vector<std::array<int, 3>>& triangles,  // closed, counter-clockwise from outside
                            double youngs_pa, double poisson, double rho_kg_m3,
                            const LowestModeSettings& settings = {});

// The same on a given 10-node mesh (kernels/fem/object_mesh.hpp's, say): `straight` when its
// mid-nodes are at their edges' midpoints (cheaper quadrature), else curved elements are
// integrated by the degree-5 rule. std::invalid_argument for a material that is not a solid's.
LowestMode lowest_free_mode_of(const Tet10Mesh& mesh, const model::Material& material,
                               const LowestModeSettings& settings = {}, bool straight = false);

// The 10-node mesh lowest_free_mode solves on (solid_mesh.cpp): TetGen's "pq1.5/12a<v>Q" fill of
// the surface, v the volume of the regular tetrahedron of edge edge_length_m, mid-nodes at the
// straight edge midpoints, shared between elements; elements positively oriented. Throws
// std::invalid_argument as above.
Tet10Mesh tetrahedralize_surface(const std::vector<std::array<double, 3>>& vertices_m,
                                 const std::vector<std::array<int, 3>>& triangles, double edge_length_m);

// The same fill's linear tetrahedra (TetGen's positive orientation; the stress solve of breakable
// bodies, kernels/fracture/).
LinearMesh tetrahedralize_linear(const std::vector<std::array<double, 3>>& vertices_m,
                                 const std::vector<std::array<int, 3>>& triangles, double edge_length_m);

// The volume enclosed by a closed, outward-oriented triangle mesh (divergence theorem), m^3;
// std::invalid_argument as above for a surface that is not closed and consistently oriented.
double enclosed_volume_m3(const std::vector<std::array<double, 3>>& vertices_m,
                          const std::vector<std::array<int, 3>>& triangles);

}  // namespace clatter::kernels::fem
