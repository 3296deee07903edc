// 003 section 3.1's quasistatic stress solve (kernels/fracture/quasistatic.hpp) on a glass slab
// 0.2 x 0.1 x 0.01 m meshed by TetGen at an edge of 5, 3 and 2 mm: the one-time assembly and
// CHOLMOD factorization, and one contact solve (eq. 3 plus the per-tet stresses). 003 reports
// 0.18-1.30 s factorizations and 0.007-0.23 s solves for 120k-630k tets.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>

#include "kernels/fracture/quasistatic.hpp"

namespace {
using namespace clatter;
using namespace clatter::kernels::fracture;

constexpr double kGlassE = 62e9, kGlassNu = 0.2, kGlassRho = 2500;
constexpr Vec3 kSlab{0.2, 0.1, 0.01};

// The slab meshed at edge_mm, once per edge.
const TetMesh& slab(int edge_mm) {
  static std::map<int, TetMesh> cache;
  auto [it, fresh] = cache.try_emplace(edge_mm);
  if (fresh) {
    std::vector<Vec3> v;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) v.push_back({kSlab[0] * i, kSlab[1] * j, kSlab[2] * k});
    // Corner i + 2j + 4k; each face's two triangles counter-clockwise seen from outside.
    const std::vector<std::array<int, 3>> tri{{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}, {0, 1, 5}, {0, 5, 4},
                                              {2, 6, 7}, {2, 7, 3}, {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
    it->second = tetrahedralize(v, tri, edge_mm * 1e-3);
  }
  return it->second;
}

void counters(benchmark::State& state, const QuasistaticSolver& solver) {
  state.counters["tets"] = static_cast<double>(solver.mesh().tets.size());
  state.counters["dofs"] = static_cast<double>(solver.dofs());
}

// arg: edge length in mm.
void BM_QuasistaticFactorize(benchmark::State& state) {
  const TetMesh& mesh = slab(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const QuasistaticSolver solver(mesh, kGlassE, kGlassNu, kGlassRho);
    benchmark::DoNotOptimize(solver.dofs());
    state.counters["factorize_s"] = solver.factorize_s();
    counters(state, solver);
  }
}

// One contact force (100 N into the top face near a corner, spread over 5 mm) per solve.
void BM_QuasistaticSolve(benchmark::State& state) {
  static std::map<int, QuasistaticSolver> solvers;
  const int edge_mm = static_cast<int>(state.range(0));
  auto it = solvers.find(edge_mm);
  if (it == solvers.end()) it = solvers.emplace(edge_mm, QuasistaticSolver(slab(edge_mm), kGlassE, kGlassNu, kGlassRho)).first;
  const QuasistaticSolver& solver = it->second;
  std::vector<NodalForce> forces;
  solver.add_surface_force(forces, {0.05, 0.03, kSlab[2]}, {10, 0, -100}, 5e-3);
  double peak_pa = 0;
  for (auto _ : state) {
    const StressField s = solver.solve(forces);
    peak_pa = s.max_principal_pa.empty() ? 0 : *std::max_element(s.max_principal_pa.begin(), s.max_principal_pa.end());
    benchmark::DoNotOptimize(peak_pa);
  }
  state.counters["peak_principal_mpa"] = peak_pa * 1e-6;
  counters(state, solver);
}

}  // namespace

BENCHMARK(BM_QuasistaticFactorize)->Arg(5)->Arg(3)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_QuasistaticSolve)->Arg(5)->Arg(3)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
