#pragma once
// The Kirchhoff surface of a solve: the field beyond the grid from the field on a closed surface
// around the body (docs/fdtd.md "The field beyond the grid"). With n the outward normal,
// r = |x - y|, r^ = (x - y)/r and every value at the retarded time t - r/c, the time-domain
// Kirchhoff integral
//   p(x, t) = 1/(4 pi) oint [ (n . r^) (p / r^2 + dp/dt / (c r)) - dp/dn / r ] dS          (K)
// holds for every x outside the surface when it encloses every source, and as R -> infinity along
// a direction d its limit, the far field,
//   F(d, tau) = lim R p(R d, tau + R/c) = 1/(4 pi) oint [ (n . d) / c dp/dt - dp/dn ](y, tau + d . y / c) dS   (F)
// is the first term q_1 of the PAN series (8).
//
// The surface is made of cell faces: those between the cells whose centres lie within a radius
// (and within an origin-centred box, where the box is tighter) and the cells outside: a closed
// staircase, its points all within the radius + dx. The box fits flat and long bodies: around the
// PAN grid's needle (semi-axes 0.5, 0.025, 0.025 m) it has 11x fewer faces than the ball, and the
// cost of hearing a point through the surface is proportional to the faces (docs/fdtd.md).
// Each element (one cell face) takes p and dp/dn at its centre from the four cells across it,
// fourth order (the scheme's own order):
//   p = (-p_{-2} + 9 p_{-1} + 9 p_0 - p_1) / 16,  dp/dn = (p_{-2} - 27 p_{-1} + 27 p_0 - p_1) / (24 dx).
// In octant mode the surface is its positive octant and the integrals add the seven mirror images
// with the field's parity (eqs. 16-21). Recording is split like the listeners' (recorder.hpp):
// each block keeps the cells it owns, and one place assembles them in a fixed order, so the result
// does not depend on how the grid was split. No MPI here.
#include <array>
#include <string>
#include <vector>

#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

// One element of the box: a cell face of area dx^2.
struct SurfaceElement {
  std::array<double, 3> centre_m{};
  int axis = 0;  // the normal's axis
  int sign = 1;  // the normal's direction along it (outward)
};

// The region the surface encloses: cell centres x with |x| <= radius_m and |x_i| <= half_box_m[i].
// Both must hold the body with the clearance the faces' four cells need (3 cells: the ball beyond
// the body's bounding sphere, the box beyond its bounding box); with the box at the radius or
// beyond it, the surface is the ball's.
struct SurfaceShape {
  double radius_m = 0;
  std::array<double, 3> half_box_m{kUnbounded, kUnbounded, kUnbounded};
  static constexpr double kUnbounded = 1e300;
};

// The elements of the surface of `shape` on `grid` (octant mode: its positive octant), in a fixed
// order. Throws std::invalid_argument if the four cells across any face would leave the grid's
// interior.
std::vector<SurfaceElement> staircase_surface(const Grid& grid, const SurfaceShape& shape);
// The radius beyond which every point is outside that surface.
double outside_radius_m(const std::vector<SurfaceElement>& elements, double dx_m);

class SurfaceRecorder {
 public:
  SurfaceRecorder(const Problem& problem, const SurfaceShape& shape, const Layout& layout, int n_samples);
  // Keeps sample n of the surface's elements whose four cells this block owns (combined into p and
  // dp/dn at once, half the memory), and of the other cells it owns that elements read.
  void record(int n, const float* pressure);
  // Whether every sample this block recorded at step n is finite.
  bool finite_at(int n) const;
  // This block's records, for the gather: (-(element + 1), p and dp/dn series) for whole elements,
  // (element * 4 + layer, the cell's series) for single cells.
  std::string pack() const;

 private:
  struct Whole {
    int element;
    std::array<long, 4> index;  // storage indices of the four cells, innermost first
    std::array<double, 4> sign;
  };
  struct Cell {
    int id;      // element * 4 + layer
    long index;  // storage index in the block's layout
  };
  std::size_t n_samples_;
  double dx_m_;
  std::vector<Whole> whole_;
  std::vector<Cell> cells_;
  std::vector<float> whole_series_;  // [whole][p, dp/dn][sample]
  std::vector<float> cell_series_;   // [cell][sample]
};

// The surface with its series: per element p and dp/dn at sample k (t_k = t_first + k dt).
struct SurfaceField {
  std::vector<SurfaceElement> elements;
  std::vector<float> p, dpdn;  // [element][sample]
  int n_samples = 0;
  double dx_m = 0, dt_s = 0, c_m_s = 0, t_first_s = 0;
  bool octant = false;
  int field = 0;  // the parity of the mirror images (octant mode)
};

// The surface of `shape` on the problem's grid with zeroed series of n_samples from t_first_s.
SurfaceField empty_surface(const Problem& problem, const SurfaceShape& shape, int n_samples, double t_first_s);
// Assembles the packs of all blocks, which together hold every cell the surface reads.
SurfaceField assemble_surface(const Problem& problem, const SurfaceShape& shape, int n_samples, double t_first_s,
                              const std::vector<std::string>& packs);

// A series on the surface field's time step: sample k at t_first_s + k dt (for the far field, the
// retarded time tau = t - R/c; it starts earlier than the record). Samples at and beyond valid_end
// needed surface values past the record's end and are left zero.
struct KirchhoffSeries {
  std::vector<double> value;
  double t_first_s = 0;
  int valid_end = 0;
};

// (F) for a unit direction d: the far field R p, in Pa m per unit acceleration. `advance_s`
// samples the series that much later: sample k holds the value at t_first_s + k dt + advance_s
// (a fraction of a step aligns a PAN direction exactly, kernels/pan/fit.hpp).
KirchhoffSeries far_field(const SurfaceField& surface, const std::array<double, 3>& d, double advance_s = 0);
// (F) for several directions, each with its own advance, in one pass over the surface per few of
// them: each series the same bits as alone, the surface's series read once for all.
struct FarListener {
  std::array<double, 3> direction{};
  double advance_s = 0;
};
std::vector<KirchhoffSeries> far_field(const SurfaceField& surface, const std::vector<FarListener>& listeners);
// (K) at a point x outside the surface (|x| > outside_radius_m), sampled like far_field.
KirchhoffSeries pressure_at(const SurfaceField& surface, const std::array<double, 3>& x_m, double advance_s = 0);
// (K) at several points in one pass over the surface: each series the same bits as alone, the
// surface's series read once for all (what a full-domain surface's hearing waits on).
std::vector<KirchhoffSeries> pressure_at(const SurfaceField& surface, const std::vector<std::array<double, 3>>& x_m,
                                         double advance_s = 0);

}  // namespace clatter::kernels::fdtd
