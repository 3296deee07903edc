#pragma once
// 003 section 3.3: the fracture impulses that turn the strain energy fracture did not consume,
// Delta E_K = E_S - E_F, into the pieces' motion (eqs. 4-5), and the "crack" the synthesizer
// renders. Everything in the broken body's own coordinates.
#include <vector>

#include "kernels/fracture/pattern.hpp"

namespace clatter::kernels::fracture {

struct PieceInertia {
  double mass_kg = 0;
  Vec3 centre_m{};
  Mat3 inertia_kg_m2{};  // about centre_m, in the body's coordinates
};

// One side of one interface: what piece `piece` receives across its boundary with `other`.
struct InterfaceImpulse {
  int piece = 0, other = 0;
  Vec3 point_m{};        // the interface's area centroid
  Vec3 impulse_n_s{};    // tau * sum of the stress forces over the interface's triangles
  double area_m2 = 0;
};

struct FractureImpulses {
  double tau_s = 0;                      // the effective duration (the energy equation's positive root)
  std::vector<Vec3> dv_m_s, dw_rad_s;    // per piece: velocity changes (eq. 5)
  std::vector<Vec3> force_n, torque_nm;  // per piece: sum of s_i, and of j_i about the piece's centre
  std::vector<InterfaceImpulse> interfaces;
  double kinetic_energy_gained_j = 0;    // recomputed from the velocity changes (= released_j)
};

// Eq. 4 with the released traction: across a triangle of area a and outward normal n, piece d
// loses the pull sigma n of its neighbour, so it receives s = -a sigma n (a piece stretched
// towards its neighbour springs away from it; 003's n is the normal into the piece). Eq. 5 and
// tau from  Delta E_K = released_j  with the pieces' pre-fracture velocities (v, w; per piece,
// body coordinates). stress_pa: per tetrahedron of the broken body's mesh. released_j <= 0 or no
// stress: tau = 0 and no change.
FractureImpulses fracture_impulses(const std::vector<FractureTriangle>& faces, const std::vector<Mat3>& stress_pa,
                                   const std::vector<PieceInertia>& pieces, const std::vector<Vec3>& v_m_s,
                                   const std::vector<Vec3>& w_rad_s, double released_j);

}  // namespace clatter::kernels::fracture
