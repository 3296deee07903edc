#pragma once
// Everything about one block's FDTD update that depends on the geometry and not on the fields:
// the leapfrog coefficients, the bulk/inner/shell boxes, the cut cells of the body (all six
// rigid-body columns, so one Operator serves every field of a proxy), the PML coefficients and the
// point source. Built once per Problem geometry and block, then only read (by Engine).
#include <array>
#include <utility>
#include <vector>

#include "kernels/fdtd/pml.hpp"
#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

// Cells the body cuts, as a structure of arrays.
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
  // Cell and rho c^2 dt^2 / dx^3 share of the monopole's volume acceleration (empty for a body).
  const std::vector<std::pair<long, float>>& point_source() const { return point_source_; }
  float c1() const { return c1_; }            // 2 - 6 lambda^2
  float lambda2() const { return lambda2_; }  // lambda^2

  struct Counts {
    long long owned = 0, bulk = 0, cut = 0, solid = 0, pml = 0;
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
  CutCells cut_;
  std::vector<std::pair<long, float>> point_source_;
  Counts counts_;
};

}  // namespace clatter::kernels::fdtd
