#pragma once
// A rigid body given as a closed, consistently oriented triangle mesh, for the cut-cell geometry
// (kernels/fdtd/geometry.hpp): its solid part along an axis-aligned line is the set of intervals
// between the line's sorted crossings with the triangles, inside where the winding number of the
// crossings so far is positive (for a closed, oriented, not self-intersecting mesh this is the
// parity rule, and it does not depend on which crossing of a tie comes first). Per axis a 2D bin
// index of the triangles' projections finds the few triangles a line can cross.
//
// A line through an edge or a vertex is decided by a fixed symbolic perturbation: the point is
// taken at (u + eps, v + eps^2) in the plane across the line (u < v the other two axes), and every
// edge's side test is evaluated with its end points in one fixed order (by vertex index), so the
// two triangles of an edge see the same value with opposite signs: such a line crosses exactly one
// of the triangles whose projections meet there (or, on a fold of the silhouette, both or none).
#include <array>
#include <vector>

#include "kernels/fdtd/geometry.hpp"

namespace clatter::kernels::fdtd {

class MeshBody final : public SolidBody {
 public:
  // `vertices_m` and `triangles` (0-based) bound the solid (io::read_obj has checked that the mesh
  // is closed, manifold and consistently oriented). The vertices are moved so that the centre of
  // mass of the uniform solid is the origin (rotation fields turn about it, in the mesh's own
  // axes); inward-facing triangles are turned outward. Throws std::invalid_argument for a mesh
  // without volume.
  MeshBody(std::vector<std::array<double, 3>> vertices_m, std::vector<std::array<int, 3>> triangles);

  Chord chord(int along, int axis_p, double p, int axis_q, double q, double lo, double hi) const override;
  BoxClass classify(const std::array<double, 3>& lo, const std::array<double, 3>& hi) const override;
  std::array<double, 3> box_lo_m() const override { return box_lo_; }
  std::array<double, 3> box_hi_m() const override { return box_hi_; }
  bool mirror_symmetric() const override { return mirror_axes_ == 7; }
  double bounding_radius_m() const override { return radius_; }
  bool contains(double x, double y, double z) const override;

  // The solid intervals {begin, end} of the whole line x[axis_p] = p, x[axis_q] = q along `along`,
  // in increasing order.
  std::vector<std::array<double, 2>> intervals(int along, int axis_p, double p, int axis_q, double q) const;
  // The input's centre of mass, subtracted from every vertex.
  const std::array<double, 3>& centre_of_mass_offset_m() const { return offset_; }
  double volume_m3() const { return volume_; }
  // The largest difference between a sampled line's solid intervals and its mirror images' found
  // by the symmetry check, relative to the bounding radius (mirror_symmetric: <= kMirrorTolerance).
  double mirror_mismatch() const { return mismatch_; }
  // The planes the mesh is mirror-symmetric in, each to kMirrorTolerance: bit a for x_a -> -x_a
  // (mirror_symmetric: all three).
  int mirror_axes() const { return mirror_axes_; }
  static constexpr double kMirrorTolerance = 1e-9;
  const std::vector<std::array<double, 3>>& vertices_m() const { return vertices_; }
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }

 private:
  // Triangles whose projection across `along` overlaps each bin of a regular nu x nv grid over the
  // bounding box's (u, v) rectangle (compressed rows).
  struct Bins {
    int u = 0, v = 0;
    double lo_u = 0, lo_v = 0, width_u = 1, width_v = 1;
    int nu = 1, nv = 1;
    std::vector<int> start, triangle;
    int bin_u(double x) const;
    int bin_v(double x) const;
  };
  struct Crossing {
    double t;
    int enter;  // +1 entering the solid with increasing t, -1 leaving
  };
  void build_bins(int along);
  void crossings(int along, double pu, double pv, std::vector<Crossing>& out) const;
  void solid_intervals(int along, int axis_p, double p, int axis_q, double q, std::vector<std::array<double, 2>>& out) const;
  std::array<double, 3> check_mirror_symmetry() const;

  std::vector<std::array<double, 3>> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<std::array<double, 6>> triangle_box_;  // lo x, y, z, hi x, y, z
  std::array<Bins, 3> bins_;
  std::array<double, 3> box_lo_{}, box_hi_{}, offset_{};
  double radius_ = 0, volume_ = 0, mismatch_ = 0;
  int mirror_axes_ = 0;
};

}  // namespace clatter::kernels::fdtd
