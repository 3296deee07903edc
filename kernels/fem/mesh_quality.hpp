#pragma once
// Quality statistics of a 10-node tetrahedral mesh.
#include "kernels/fem/assembly.hpp"

namespace clatter::kernels::fem {

struct MeshQuality {
  double max_radius_edge = 0, mean_radius_edge = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  double min_jacobian_ratio = 0;  // over elements: min det J / max det J, sampled at nodes and quadrature points
  long long elements = 0, nodes = 0, dofs = 0;
  double edge_length_m = 0;  // the h used (after the cap)
};

// Radius-edge ratio and dihedral angles of the straight tetrahedra through the vertices; the
// Jacobian ratio of the curved elements from det J at their 10 nodes and the 15 Keast points (det J
// is a cubic in the reference coordinates, so the samples bound it well but not exactly).
MeshQuality mesh_quality(const Tet10Mesh& mesh);

// min det J / max det J over the samples above, for one element; <= 0 when it folds.
double jacobian_ratio(const Tet10Coords& x_m);

// One element's share of the statistics above.
struct ElementQuality {
  double radius_edge = 0, min_dihedral_deg = 0, max_dihedral_deg = 0, jacobian_ratio = 0;
};
ElementQuality element_quality(const Tet10Coords& x_m);

}  // namespace clatter::kernels::fem
