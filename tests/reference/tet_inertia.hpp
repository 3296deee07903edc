#pragma once
// The mass, centre and inertia of a uniform tetrahedral mesh, summed over its tetrahedra: the
// tests' volumetric reference for the fracture pieces, independent of the surface integrals of
// kernels/mass_properties.cpp that the simulator uses.
#include "kernels/fracture/impulses.hpp"

namespace clatter::reference {

kernels::fracture::PieceInertia tet_mesh_inertia(const kernels::fracture::TetMesh& mesh, double rho_kg_m3);

}  // namespace clatter::reference
