#pragma once
// The FDTD time stepper for one rank's block: the pressure-only leapfrog
//   p^{n+1} = 2 p^n - p^{n-1} + lambda^2 (sum of the 6 neighbours - 6 p^n)
// in the bulk (12 bytes of memory traffic per cell update), cut cells carrying the rigid-body
// boundary condition (eq. 9), and the PML. MPI-free: the caller exchanges the halo of pressure()
// between the phases of a step (jobs/solve_job.cpp):
//   begin_step(); update_bulk(inner_box()); <halo arrives>; update_bulk(shell boxes);
//   finish_step(t_n);
#include <memory>
#include <vector>

#include "kernels/fdtd/pml.hpp"
#include "kernels/fdtd/problem.hpp"

namespace clatter::kernels::fdtd {

class Solver {
 public:
  Solver(const Problem& problem, const Box& owned);

  // Zeroes every field and selects rigid-body field 1..6 of the same body (0 for a monopole
  // problem), so one Solver serves every field of a run: its geometry, layer and storage are built
  // once. The constructor starts problem.field.
  void start(int field);

  const Layout& layout() const { return layout_; }
  const Problem& problem() const { return problem_; }
  float* pressure() { return now_.data(); }  // p at t_n, with its one-cell halo
  const float* pressure() const { return now_.data(); }
  float value(const std::array<int, 3>& cell) const { return now_[static_cast<std::size_t>(layout_.at(cell))]; }

  // Fills the mirror ghosts (octant mode) and keeps p^{n-1} of the cut cells.
  void begin_step();
  // Bulk cells of this rank that read no halo value, and the rest of them.
  const Box& inner_box() const { return inner_; }
  const std::vector<Box>& shell_boxes() const { return shell_; }
  void update_bulk(const Box& box);
  // The PML, the cut cells and the source at t_n (psi(t_n; h)); then p^{n+1} becomes pressure().
  void finish_step(double t_s);

  struct Counts {
    long long owned = 0, bulk = 0, cut = 0, solid = 0, pml = 0;
    std::size_t bytes = 0;  // field and auxiliary storage of this rank
  };
  const Counts& counts() const { return counts_; }

 private:
  void build_cut_cells();
  void fill_mirror_ghosts();
  void update_cut_cells(float psi);

  Problem problem_;
  Layout layout_;
  std::vector<float> now_, next_;  // p^n and (p^{n-1} -> p^{n+1})
  Box bulk_, inner_;
  std::vector<Box> shell_;
  std::unique_ptr<Pml> pml_;
  float c1_, lambda2_;  // 2 - 6 lambda^2, lambda^2

  struct CutCells {  // structure of arrays
    std::vector<long> index;
    std::vector<float> gain;                 // lambda^2 / beta_eff
    std::vector<std::array<float, 6>> alpha;
    std::vector<std::array<float, 6>> body_all;  // -(rho c^2 dt^2 / (beta_eff dx)) * body flux, fields 1..6
    std::vector<float> body;                 // the started field's column of body_all
    std::vector<float> old;                  // p^{n-1}, kept before the bulk overwrites it
  } cut_;
  std::vector<std::pair<long, float>> point_source_;  // cell, rho c^2 dt^2 / dx^3 share
  Counts counts_;
};

}  // namespace clatter::kernels::fdtd
