#pragma once
// The FDTD time stepper of one block: in the bulk the pressure-only two-step update of the
// Operator's scheme (srl: 7 points; me4: 25 points, fourth order; 12 bytes of memory traffic per
// cell update either way), cut cells carrying the rigid-body boundary condition (eq. 9) and a
// band of 7-point cells around them, and the PML, with the coefficients of an Operator. The Engine owns
// the fields; its halo is filled through a HaloExchange (core/halo_exchange.hpp), so it runs the
// same under MPI, between serial blocks in a test, or alone.
#include <cstddef>
#include <vector>

#include "core/halo_exchange.hpp"
#include "kernels/fdtd/operator.hpp"

namespace clatter::kernels::fdtd {

// Where the CPU has AVX-512VL the me4 bulk runs its register-blocked row kernel; elsewhere the
// portable rows (AVX2 or baseline clones), with the same bits. Tests switch the first off to check
// the second's bits on a machine that has AVX-512VL. Not for use while an Engine steps.
void use_portable_row_kernels(bool on);

class Engine {
 public:
  // Both must outlive the Engine. Starts the field of op.problem().
  Engine(const Operator& op, HaloExchange& halo);

  // Back to rest with rigid-body field 1..6 of the operator's body (0 for a monopole operator).
  void start(int field);
  // p^n -> p^{n+1}, driven by the source at t_s = t_n (psi(t_n; h)).
  void step(double t_s);

  int field() const { return field_; }
  const Layout& layout() const { return op_.layout(); }
  const float* pressure() const { return now_.data(); }  // p at t_n, with its halo
  float value(const std::array<int, 3>& cell) const { return now_[static_cast<std::size_t>(layout().at(cell))]; }

 private:
  void fill_z_mirror_ghosts();
  void fill_mirror_ghosts();
  void keep_cut_cell_old();
  // The interior (interior = true) also takes, as it goes, the rows of the PML's z layers within its
  // x-y extent (Pml::update_z_rows) and, plane by plane, its cut cells, driven by psi.
  void update_bulk(const Box& box, bool interior = false, float psi = 0.0f);
  void update_bulk_srl(const Box& box, bool interior, float psi);
  void update_bulk_me4(const Box& box, bool interior, float psi);
  void update_interior_cut_cells(int i, float psi);
  // The cut cells of the given slots of op_.cut_cells().
  void update_cut_cells(float psi, const std::size_t* first, const std::size_t* last);
  void add_point_source(float psi, float psi_smooth);

  const Operator& op_;
  HaloExchange& halo_;
  int field_ = 0;
  HugeVector now_, next_;  // p^n and (p^{n-1} -> p^{n+1}), on huge pages where the system has them
  PmlState pml_;
  std::vector<float> cut_body_;  // the started field's column of the operator's body_all
  std::vector<float> cut_old_;   // p^{n-1} of the cut cells, kept before the bulk overwrites it
  // Slots of the cut cells within the inner box, plane by plane (those of plane inner.lo[0] + n
  // from interior_cut_start_[n] on), and of the others, updated after the shell and the PML.
  std::vector<std::size_t> interior_cut_, interior_cut_start_, other_cut_;
};

}  // namespace clatter::kernels::fdtd
