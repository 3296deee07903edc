// clatter-pan-direction-study: how many directions an adaptive direction set needs (issue 32,
// docs/pan.md "Adaptive directions"). One proxy's solve at a PAN config's resolution; per field,
// the far field (heard through the Kirchhoff surface, aligned like a bank's directions) is
// interpolated quadratically over the uniform layouts and over the layout refined at split points
// (banks/pan refine_directions), and compared with the far field itself at random test directions
// that are no vertex of any of them. Prints one CSV row per field and direction set.
//
//   mpiexec -n 2 clatter-pan-direction-study [-c configs/pan.toml] --proxy 0.2625,0.12 --fields 1,4
//       [--tolerance 0.02] [--levels 3] [--tests 256] [--set key=value ...]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "analysis/pan_study_options.hpp"
#include "banks/pan/pan_job.hpp"
#include "banks/pan/pan_spec.hpp"
#include "kernels/pan/direction_mesh.hpp"
#include "mpi/session.hpp"

namespace {

using namespace clatter;
namespace pan = kernels::pan;

int study(mpi::Session& session, int argc, char** argv) {
  CLI::App app{"clatter-pan-direction-study: adaptive against uniform direction sets (issue 32)"};
  analysis::PanStudyOptions options;
  std::vector<int> fields{1};
  double tolerance = 0.02;
  int levels = 3, tests = 256;
  options.add_to(app);
  app.add_option("--fields", fields, "fields 1-6")->delimiter(',');
  app.add_option("--tolerance", tolerance, "refine where a split point misses by more than this (relative L2)");
  app.add_option("--levels", levels, "splits below a root at most");
  app.add_option("--tests", tests, "random test directions");
  CLI11_PARSE(app, argc, argv);
  io::Config config = options.config();
  std::string list = "solve.fields=[";
  for (std::size_t i = 0; i < fields.size(); ++i) list += (i ? ", " : "") + std::to_string(fields[i]);
  config.set(list + "]");
  const auto spec = jobs::make_pan_spec(config);
  jobs::SolveSpec s = spec.solve;
  s.problem.body = {spec.a_m, spec.bodies[0].b_m, spec.bodies[0].c_m};
  if (session.is_root()) std::printf("field,set,directions,splits,far_fields,median_pct,p90_pct,worst_pct,above_5pct\n");
  auto hook = [&](std::size_t fi, const kernels::fdtd::SurfaceField& surface) {
    const auto refined = jobs::refine_directions(spec, 0, surface, tolerance, levels, 5000);
    // Test directions: random in the octant, none on a vertex (probability zero).
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::array<double, 3>> points;
    std::vector<std::vector<double>> truth;
    const double floor = jobs::far_field_floor(spec, 0, surface);
    for (int i = 0; i < tests; ++i) {
      std::array<double, 3> d{u(rng), u(rng), u(rng)};
      const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (double& x : d) x /= n;
      points.push_back(d);
      truth.push_back(jobs::aligned_far_field(spec, 0, surface, d));
    }
    auto report = [&](const std::string& name, const pan::DirectionMesh& mesh, int splits, std::size_t far_fields) {
      std::vector<std::vector<double>> at(mesh.size());
      // As the bank stores and interpolates them: over the symmetry zeros, then times them.
      for (std::size_t v = 0; v < mesh.size(); ++v) at[v] = jobs::stored_far_field(spec, 0, surface, mesh.direction(v));
      std::vector<double> misses;
      std::vector<double> sum(spec.length);
      for (std::size_t i = 0; i < points.size(); ++i) {
        pan::blend(mesh.locate(points[i]), [&](std::size_t v) -> const std::vector<double>& { return at[v]; }, sum);
        for (double& x : sum) x *= pan::symmetry_zeros(surface.field, points[i]);
        misses.push_back(jobs::far_field_miss(sum, truth[i], floor));
      }
      int above = 0;
      for (double m : misses) above += m > 0.05;
      std::printf("%d,%s,%zu,%d,%zu,%.2f,%.2f,%.2f,%d\n", s.fields[fi], name.c_str(), mesh.size(), splits, far_fields,
                  100 * analysis::percentile(misses, 0.5), 100 * analysis::percentile(misses, 0.9), 100 * analysis::percentile(misses, 1.0), above);
      std::fflush(stdout);
    };
    for (int d : {spec.divisions, 2 * spec.divisions, 4 * spec.divisions}) report("uniform-" + std::to_string(d), pan::DirectionMesh(d, 0), 0, 0);
    report("adaptive", refined.mesh, refined.splits, refined.far_fields.size());
  };
  jobs::run_solve(session.world(), s, 0, hook);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return clatter::mpi::run(argc, argv, "clatter-pan-direction-study",
                           [&](clatter::mpi::Session& session) { return study(session, argc, argv); });
}
