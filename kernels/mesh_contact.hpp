#pragma once
// The radius of curvature a closed triangle mesh presents at a contact point, for Hertz contact
// (kernels/contact.hpp): the object's own geometry instead of its proxy ellipsoid's (seed 000
// section 2.2.1, seed 004: "the object's local radius of curvature"). docs/synth.md "Contact"
// states the rule and its numbers.
//
// The point is first projected to the nearest point of the surface. Then:
//  - sharp features: an edge whose two faces' normals differ by more than sharp_angle_rad is sharp;
//    a vertex where three or more sharp edges meet (or two that turn by more than that angle) is a
//    corner. A contact within rounding_radius_m of a corner is a corner contact: a sphere of that
//    radius, R = r_min. Else within r_min of a sharp edge: a cylinder of radius r_min along the
//    edge, flat along it, R = sqrt(r_min R_flat).
//  - elsewhere (smooth or flat): principal curvatures from a least-squares height field over the
//    contact face's plane, fitted to the vertices of the surrounding smooth patch (never across a
//    sharp edge) within fit_edges of the contact face's shortest edges, at least the 30 nearest
//    (within twice that): quartic, to heights, where there are 30; else a quadric to heights and
//    vertex normals. Each principal curvature is clamped to [1 / R_flat, 1 / r_min] (flat, saddle
//    or concave directions count as R_flat), and R = 1 / sqrt(kappa_1 kappa_2), the Hertz
//    equivalent radius sqrt(R1 R2).
// Nothing here returns NaN: bad meshes and points far from the surface throw; a fit the vertices
// leave undetermined counts as flat.
#include <array>
#include <vector>

#include "kernels/rigid_body.hpp"

namespace clatter::kernels {

struct MeshContactRule {
  double rounding_radius_m = 0;  // r_min: the rounding of sharp edges and corners, > 0
  double flat_radius_m = 0;      // R_flat: the largest radius of curvature, >= r_min
  double sharp_angle_rad = 0.5235987755982988;  // 30 degrees between the normals of two faces
  double fit_edges = 2.5;        // the fit's neighbourhood radius, in the contact face's shortest edges
  double max_offset_m = 0;       // a contact point farther from the surface than this throws
};

// r_min and R_flat of an object (docs/synth.md "Contact"): r_min = 2 % of the volume-equivalent
// radius (3 V / 4 pi)^(1/3); R_flat = a b / c of its proxy ellipsoid (a >= b >= c), the largest
// radius of curvature the proxy has (at the end of its shortest axis); max_offset_m = half the
// largest distance of a vertex from the centroid. Throws std::invalid_argument for volume <= 0.
MeshContactRule mesh_contact_rule(const ProxyFit& proxy, double volume_m3, const std::vector<Vec3>& vertices_m,
                                  const Vec3& centroid_m);

enum class ContactFeature { smooth, edge, corner };
const char* to_string(ContactFeature f);

struct MeshContactPoint {
  ContactFeature feature = ContactFeature::smooth;
  double radius_m = 0;          // the Hertz equivalent radius sqrt(R1 R2)
  double curvature_1_per_m = 0;  // principal curvatures after the clamps, kappa_1 >= kappa_2
  double curvature_2_per_m = 0;
  Vec3 surface_point_m{};       // the nearest surface point, mesh frame
  double offset_m = 0;          // its distance from the given point
};

class MeshContact {
 public:
  // Vertices and triangles as for mesh_mass_properties (closed, consistently oriented, outward
  // normals). Throws std::invalid_argument for an edge not shared by exactly two triangles, a mesh
  // of zero-area triangles only, or a rule with r_min <= 0 or R_flat < r_min.
  MeshContact(std::vector<Vec3> vertices_m, std::vector<std::array<int, 3>> triangles, const MeshContactRule& rule);

  // At a point in the mesh's frame. Throws std::invalid_argument (saying how far) for a point
  // farther than rule.max_offset_m from the surface.
  MeshContactPoint at(const Vec3& point_m) const;

  const MeshContactRule& rule() const { return rule_; }

 private:
  struct Nearest {
    int face = -1;
    Vec3 point{};
    double distance = 0;
  };
  Nearest nearest(const Vec3& p) const;
  std::array<double, 2> fitted_curvatures(int face, const Vec3& q) const;  // kappa_1 >= kappa_2, unclamped
  Vec3 patch_normal(int vertex, int component) const;

  std::vector<Vec3> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  MeshContactRule rule_;
  std::vector<Vec3> face_normals_;                // unit; zero for a zero-area face
  std::vector<std::array<int, 3>> neighbours_;    // the face across edge (k, k+1)
  std::vector<std::array<bool, 3>> sharp_;        // edge (k, k+1) sharp
  std::vector<int> component_;                    // smooth patch: faces joined across non-sharp edges
  std::vector<std::vector<int>> vertex_faces_;
  std::vector<bool> corner_;
};

}  // namespace clatter::kernels
