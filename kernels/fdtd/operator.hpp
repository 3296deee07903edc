#pragma once
// Everything about one block's FDTD update that depends on the geometry and not on the fields:
// the scheme's coefficients, the bulk/inner/shell boxes, the cut cells of the body (all six
// rigid-body columns, so one Operator serves every field of a proxy) with the band of fluid cells
// around them that the fourth-order stencil may not reach across, the PML coefficients and the
// point source. Built once per Problem geometry and block, then only read (by Engine).
#include <array>
#include <utility>
#include <vector>

#include "kernels/fdtd/pml.hpp"
#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

// Cells updated by the finite-volume 7-point form: the cells the body cuts and, with the me4
// scheme, the fluid cells whose 25-point stencil would reach a cut or solid cell (faces all open,
// no body flux). A structure of arrays.
struct CutCells {
  std::vector<long> index;                      // storage index in the block's layout
  std::vector<float> gain;                      // lambda^2 / beta_eff
  std::vector<std::array<float, 6>> alpha;      // open fraction of the faces -x, +x, -y, +y, -z, +z
  std::vector<std::array<float, 6>> body_all;   // -(rho c^2 dt^2 / (beta_eff dx)) * body flux, fields 1..6
};

class Operator {
 public:
  // problem.field only selects the kind: 0 a monopole (no body), 1..6 any field of the body.
  Operator(const Problem& problem, const Box& owned);

  const Problem& problem() const { return problem_; }
  const Layout& layout() const { return layout_; }
  // Bulk cells of this block that read no halo value, and the rest of them as disjoint slabs.
  const Box& inner_box() const { return inner_; }
  const std::vector<Box>& shell_boxes() const { return shell_; }
  const Pml& pml() const { return pml_; }
  const CutCells& cut_cells() const { return cut_; }
  // The monopole's cells (empty for a body): each adds psi_smooth x `smoothed` + psi(t_n) x `now`
  // to p^{n+1}, psi_smooth = (psi(t_n - dt) + 10 psi(t_n) + psi(t_n + dt)) / 12 (docs/fdtd.md).
  struct SourceCell {
    long index = 0;
    float smoothed = 0, now = 0;
  };
  const std::vector<SourceCell>& point_source() const { return point_source_; }
  float c1() const { return c1_; }            // 2 - 6 lambda^2
  float lambda2() const { return lambda2_; }  // lambda^2
  // The me4 update p+ = c0 p + c1 (6 axis neighbours) + c2 (6 at distance 2) + c3 (12 face
  // diagonals) - p-, from lambda^2 L4 + (lambda^4 / 12) L2^2 (docs/fdtd.md).
  struct Me4 {
    float c0 = 0, c1 = 0, c2 = 0, c3 = 0;
  };
  const Me4& me4() const { return me4_; }
  // me4 only: per axis and global cell index, the weight theta of the 7-point update in the cells
  // before the PML, rising smoothly from 0 to 1 over blend_cells() cells so that the scheme meets
  // the (7-point) layer gradually instead of reflecting at an abrupt change of dispersion. A cell
  // uses the largest theta of its three indices: p+ = me4 + theta (srl - me4).
  const std::array<std::vector<float>, 3>& blend() const { return blend_; }

  struct Counts {
    long long owned = 0, bulk = 0, cut = 0, band = 0, solid = 0, pml = 0;
    std::size_t bytes = 0;  // this operator's and one engine's storage
  };
  const Counts& counts() const { return counts_; }

 private:
  void split_bulk(const Box& owned);
  void build_cut_cells();
  void build_point_source();

  Problem problem_;
  Layout layout_;
  Box bulk_, inner_;
  std::vector<Box> shell_;
  Pml pml_;
  float c1_ = 0, lambda2_ = 0;
  Me4 me4_;
  std::array<std::vector<float>, 3> blend_;
  CutCells cut_;
  std::vector<SourceCell> point_source_;
  Counts counts_;
};

}  // namespace clatter::kernels::fdtd
