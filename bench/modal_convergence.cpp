// clatter-modal-convergence: the first distinct frequencies of one normalized glass ellipsoid on the
// modal bank's mesh (banks/modal/modal_job.hpp mesh_entry) at a given h and number of quadratic
// elements through the thinnest axis, for the convergence tables of docs/modal.md ("Defaults and
// why"). One rank; the lowest eigenpairs above the rigid motions by one shift-and-invert solve.
//   clatter-modal-convergence A,B,C ELEMENTS_THROUGH_THICKNESS H_M [DISTINCT] [KEY=VALUE ...] [--estimate]
// (A,B,C proportional; KEY=VALUE sets a modal config key, e.g. mesh.layered_below_ratio=0;
// --estimate: the pre-solve's mesh of that h, as the bank's estimate_first_mode makes it)
// prints one line: dofs, mesh/assembly/solve seconds, worst relative residual, then the first
// DISTINCT (default 10) distinct frequencies [Hz] (modes closer than modes.cluster_gap are one).
#include <fmt/format.h>
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "banks/modal/modal_fem.hpp"
#include "banks/modal/modal_job.hpp"
#include "banks/modal/modal_spec.hpp"
#include "io/config.hpp"
#include "petsc/eigen.hpp"
#include "petsc/session.hpp"

namespace {
using namespace clatter;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int run(const std::string& axes_text, double through, double h_m, int distinct, const std::vector<std::string>& sets,
        bool estimate) {
  io::Config config(jobs::modal_schema());
  config.set("patch.min_ratio=0.01");
  for (const auto& s : sets) config.set(s);
  double a = 0, b = 0, c = 0;
  if (std::sscanf(axes_text.c_str(), "%lf,%lf,%lf", &a, &b, &c) != 3) throw std::invalid_argument("A,B,C: three numbers");
  const double norm = std::sqrt(a * a + b * b + c * c);  // proportional axes, normalized here
  config.set(fmt::format("patch.samples=[[{:.17g}, {:.17g}, {:.17g}]]", a / norm, b / norm, c / norm));
  const jobs::ModalSpec spec = jobs::make_modal_spec(config);
  const auto& axes = spec.samples_m.front();
  auto t0 = std::chrono::steady_clock::now();
  const auto mesh = jobs::mesh_entry(spec, axes, h_m, through, estimate ? jobs::MeshFor::estimate : jobs::MeshFor::entry);
  const double mesh_s = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const auto model = jobs::assemble_fem(MPI_COMM_SELF, mesh.mesh, spec.header.material);
  const double assembly_s = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  // Modes with doublets: twice the distinct count and some margin.
  petsc::LowestSettings settings;
  settings.count = 2 * distinct + 4;
  settings.tolerance = spec.header.solve.tolerance;
  const double sphere_lambda = std::pow(2.5 * spec.header.material.shear_speed_m_s() * axes[0] / (axes[2] * axes[2]), 2);
  settings.shift = -0.25 * sphere_lambda;
  const auto solution = petsc::lowest_eigenpairs(model.K, model.M, settings, model.rigid);
  const double solve_s = seconds_since(t0);
  double worst = 0;
  for (double r : solution.relative_residuals) worst = std::max(worst, r);
  std::string line = fmt::format("axes {:.6f},{:.6f},{:.6f} through {} h {:.5f} dofs {} mesh_s {:.1f} assembly_s {:.1f} "
                                 "solve_s {:.1f} residual {:.1e} f_hz",
                                 axes[0], axes[1], axes[2], through, mesh.quality.edge_length_m, mesh.quality.dofs, mesh_s,
                                 assembly_s, solve_s, worst);
  double last = -1;
  int found = 0;
  for (double lambda : solution.lambdas) {
    const double f = jobs::frequency_hz(lambda);
    if (last > 0 && f <= last * (1 + spec.header.solve.cluster_gap)) continue;
    last = f;
    line += fmt::format(" {:.6g}", f);
    if (++found == distinct) break;
  }
  std::puts(line.c_str());
  return found == distinct ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fputs("usage: clatter-modal-convergence A,B,C ELEMENTS_THROUGH_THICKNESS H_M [DISTINCT] [KEY=VALUE ...] [--estimate]\n", stderr);
    return 2;
  }
  MPI_Init(&argc, &argv);
  int rc = 0;
  {
    const petsc::Session session(MPI_COMM_SELF);
    try {
      int distinct = 10;
      std::vector<std::string> sets;
      bool estimate = false;
      for (int i = 4; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--estimate")
          estimate = true;
        else if (arg.find('=') != std::string::npos)
          sets.push_back(arg);
        else
          distinct = std::stoi(arg);
      }
      rc = run(argv[1], std::stod(argv[2]), std::stod(argv[3]), distinct, sets, estimate);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "clatter-modal-convergence: %s\n", e.what());
      rc = 1;
    }
  }
  MPI_Finalize();
  return rc;
}
