#pragma once
// 003 section 3.2's energy-bounded fracture pattern: Voronoi-like regions grown on the nodes of the
// body's tetrahedral mesh from seeds sampled by strain energy density, one seed added at a time
// while the fracture energy G_c A_F stays within eta E_S; the multi-region tetrahedra split along
// their dual cells, so the pieces come out as conforming tetrahedral meshes whose fracture
// surfaces match triangle for triangle.
#include <array>
#include <cstdint>
#include <vector>

#include "kernels/fracture/tet_mesh.hpp"

namespace clatter::kernels::fracture {

struct PatternSettings {
  double fracture_energy_j_m2 = 0;  // G_c (> 0)
  double eta = 0.8;                 // share of the strain energy fracture may consume, (0, 1]
  double alpha = 0.15;              // region weight k_i = (energy density at seed i)^alpha, >= 0
  std::uint64_t seed = 1;           // of the seed sampling
  int max_pieces = 2000;            // stop adding seeds here too
  // Stop adding seeds before a piece would be smaller than this (0: no bound): the stress mesh
  // must resolve the pieces it makes (a piece of a few tetrahedra has no meaningful stress).
  double min_piece_volume_m3 = 0;
  // Where non-empty: the seed nodes, in insertion order, instead of the sampled ones (distinct
  // node indices; a scene that wants a crack at a known place, and the tests).
  std::vector<int> seed_nodes;
};

struct FractureTriangle {
  std::array<Vec3, 3> points_m;  // counter-clockwise seen from outside `piece` (outward normal of piece)
  int piece = 0, other = 0;      // the pieces on either side (indices into FracturePattern::pieces)
  int tet = 0;                   // the input mesh's tetrahedron it lies in (whose stress acts on it)
};

struct Piece {
  TetMesh mesh;                             // its tetrahedra (whole input tets and parts of cut ones), nodes compacted
  std::vector<int> source_tets;             // per tet of `mesh`: the input tetrahedron it lies in
  std::vector<std::array<int, 3>> surface;  // its closed outward boundary, over mesh.nodes_m
};

struct FracturePattern {
  std::vector<Piece> pieces;                         // empty: no pattern of 2+ pieces satisfies G_c A_F <= eta E_S
  std::vector<FractureTriangle> fracture_triangles;  // every interface triangle twice, once per side
  double area_m2 = 0;                                // A_F, each interface counted once
  double fracture_energy_j = 0;                      // G_c A_F
  int seeds = 0;                                     // seeds of the returned pattern (= pieces.size())
};

// energy_density_j_m3: per tet (>= 0); strain_energy_j: E_S of the body.
// Seeds are nodes drawn without repetition with probability proportional to nodal energy density
// times nodal volume; every node joins the region that reaches it first by the weighted geodesic
// distance k_i * (edge path length), grown from all seeds at once (so every region is connected).
// A tetrahedron whose nodes lie in several regions is cut into its 4 vertex dual cells; the
// single-region tetrahedra around the cut edges are coned from their centroid so that the pieces
// stay conforming. std::invalid_argument for inconsistent input or a mesh that is not connected.
FracturePattern fracture_pattern(const TetMesh& mesh, const std::vector<double>& energy_density_j_m3,
                                 double strain_energy_j, const PatternSettings& settings);

}  // namespace clatter::kernels::fracture
