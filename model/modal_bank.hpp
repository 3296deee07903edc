#pragma once
// The modal soundbank (003 §5, Appendix E) as plain data: the one definition that io/ reads and
// writes (format "clatter-modal-bank", docs/bank-format.md), jobs/ builds and the synthesizer will
// render from. Per normalized ellipsoid (a <= b <= c, a^2 + b^2 + c^2 = 1 m^2) of one material:
// every free vibration mode in [f_1, f_max], with its mass-normalized shape on the surface.
// Numbers and vectors only; std only.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/material.hpp"
#include "model/sweep_status.hpp"

namespace clatter::model {

// The quality of the tetrahedral mesh an entry was solved on (kernels/fem/mesh_quality.hpp).
struct ModalMeshStats {
  std::int64_t elements = 0, nodes = 0, dofs = 0;
  double edge_length_m = 0;  // target h inside; the surface spacing follows the curvature
  double max_radius_edge = 0, mean_radius_edge = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  double min_jacobian_ratio = 0;
};

// How the eigen-solve of an entry was set up and what its count check saw.
struct ModalSolveRecord {
  double lambda_lo = 0, lambda_hi = 0;     // the sliced interval of omega^2 [rad^2/s^2]
  std::int64_t below_lo = 0, below_hi = 0; // eigenvalues below each end, by inertia (below_lo: the 6 rigid motions)
  std::int64_t found_in_interval = 0;      // modes the solve returned in [lambda_lo, lambda_hi] (= below_hi -
                                           // below_lo); the entry keeps those from f_1 to f_max
  std::int64_t shifts = 0;                 // shifts factorised
  double first_mode_estimate_hz = 0;       // f_1 from the coarse pre-solve that set h and the interval
  std::string solver_options;              // the PETSc/SLEPc options of the solve
};

// Wall times and memory of an entry: provenance of one run, left out of the content hash.
struct ModalEntryCost {
  double mesh_s = 0, assembly_s = 0, estimate_s = 0, solve_s = 0, total_s = 0;  // solve_s: basis rule included
  double factor_memory_mb = 0;  // MUMPS' INFOG(21) (10^6 bytes), largest rank, count-check factorisation
  double memory_max_mb = 0;     // resident memory after the solve, largest rank (10^6 bytes)
  std::int32_t ranks = 0;
};

struct ModalEntry {
  std::uint32_t sample = 0;                // index in the config's patch.samples (task eNNN)
  std::array<double, 3> axes_m{};          // semi-axes a <= b <= c, a^2 + b^2 + c^2 = 1
  std::vector<double> frequencies_hz;      // ascending, f_1 .. f_max
  std::vector<double> damping_ratios;      // the bank material's Rayleigh damping at each frequency
  std::vector<std::int32_t> cluster;       // per mode: its multiplet (modes within the cluster gap), 0-based
  std::vector<double> relative_residuals;  // ||K u - lambda M u|| / ||K u||
  // The curved surface: nodes and 6-node triangles (vertices counter-clockwise from outside,
  // then the mid-nodes of edges 01, 12, 20).
  std::vector<std::array<double, 3>> surface_nodes_m;
  std::vector<std::array<std::int32_t, 6>> surface_faces;
  // [mode][surface node][3]: mass-normalized displacement (u^T M u = 1) [kg^-1/2], the sign and
  // basis rule of kernels/modal/mode_basis.hpp applied.
  std::vector<double> shapes;
  ModalMeshStats mesh;
  ModalSolveRecord solve;
  ModalEntryCost cost;

  std::size_t modes() const { return frequencies_hz.size(); }
};

// What every entry of a bank shares: the material and the settings that decide its content.
struct ModalBankHeader {
  Material material;
  double f_max_multiple = 0;           // f_max = f_max_multiple * f_1, per entry
  double elements_per_wavelength = 0;  // h = shear wavelength at f_max / this
  double min_ratio = 0;                // smallest a/c of the sampled patch
  double cluster_gap = 0;              // relative frequency gap that separates multiplets
  double degenerate_gap = 0;           // Ritz values closer than this get the reference-field basis
  double coarse_edge_m = 0;            // h of the pre-solve that estimates f_1
  double solver_tolerance = 0;         // SLEPc's -eps_tol
  double residual_limit = 0;           // every mode's relative residual is at most this
  std::int32_t ranks_per_task = 0;     // ranks that solved each entry (shapes agree across it to ~1e-8)
  std::string solver_libraries;        // e.g. "PETSc 3.18.5, SLEPc 3.18.2": the last bits depend on them
};

struct ModalBank {
  ModalBankHeader header;
  std::vector<ModalEntry> entries;     // in the order of the config's samples; failed ones absent (/sweep)
  SweepStatus sweep;
};

}  // namespace clatter::model
