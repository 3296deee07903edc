// clatter-pan-direction-study: how many directions an adaptive direction set needs (issue 32,
// docs/pan.md "Adaptive directions"). One proxy's solve at a PAN config's resolution; per field,
// the far field (heard through the Kirchhoff surface, aligned like a bank's directions) is
// interpolated quadratically over the uniform layouts and over the layout refined at split points
// (banks/pan refine_directions), and compared with the far field itself at random test directions
// that are no vertex of any of them. Prints one CSV row per field and direction set.
// With --point x,y,z (repeatable), it splits a bank's error at that listener into its parts
// instead, each a relative L2 over the record against R p heard there through the surface:
//   radial       the radial model (a cubic in 1/R through the far field and the fit's radii) at
//                the point's own direction, no interpolation between directions;
//   dir_far      the far field interpolated over the set refined to --tolerance
//                at the point's direction, against the far field there;
//   dir_here     R p at the point's radius interpolated the same way from the six nodes of the
//                leaf holding the direction, each heard at that radius.
//
//   mpiexec -n 2 clatter-pan-direction-study [-c configs/pan.toml] --proxy 0.2625,0.12 --fields 1,4
//       [--tolerance 0.02] [--levels 3] [--tests 256] [--point 2.7,1.4,2.4 ...] [--set key=value ...]
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
#include "kernels/pan/directions.hpp"
#include "kernels/pan/fit.hpp"
#include "kernels/pan/radial.hpp"
#include "mpi/session.hpp"

namespace {

using namespace clatter;
namespace pan = kernels::pan;
namespace fdtd = kernels::fdtd;

// R p(R, tau + R/c + h(d)/c) at R d, over the symmetry zeros: a direction as a bank stores it
// (aligned by its support distance h), on retarded-time samples tau = k dt. R = 0: the far field.
// Whole steps index, the fraction goes to the surface's delay sums.
std::vector<double> stored_series(const jobs::PanSpec& spec, const fdtd::SurfaceField& surface, const std::array<double, 3>& d,
                                  double r_m, int samples) {
  const double dt = spec.solve.problem.dt_s, c = spec.solve.problem.c_m_s;
  const auto& body = spec.bodies[0];
  const auto heard = pan::off_planes(surface.field, d);
  // Sample n at tau_n + R/c - h/c, tau_n = (n - samples / 4) dt: whole steps index, the
  // fraction goes to the surface's delay sums (kirchhoff.hpp: sample k at t_first + k dt + advance).
  const double shift = r_m / (c * dt) - pan::support_delay_samples(heard, spec.a_m, body.b_m, body.c_m, body.shape, c, dt);
  const long whole = static_cast<long>(std::floor(shift));
  const double fraction_s = (shift - static_cast<double>(whole)) * dt;
  const auto series = r_m > 0 ? fdtd::pressure_at(surface, {r_m * heard[0], r_m * heard[1], r_m * heard[2]}, fraction_s)
                              : fdtd::far_field(surface, heard, fraction_s);
  const double scale = (r_m > 0 ? r_m : 1.0) / pan::symmetry_zeros(surface.field, heard);
  const long first = std::lround(series.t_first_s / dt) - whole + samples / 4;
  std::vector<double> out(static_cast<std::size_t>(samples), 0.0);
  for (long k = 0; k < series.valid_end; ++k) {
    const long n = k + first;
    if (n >= 0 && n < samples) out[static_cast<std::size_t>(n)] = series.value[static_cast<std::size_t>(k)] * scale;
  }
  return out;
}

struct Parts {
  double r_m = 0, radial = 0, dir_far = 0, dir_here = 0;
};

Parts error_parts(const jobs::PanSpec& spec, const fdtd::SurfaceField& surface, const pan::DirectionMesh& mesh,
                  const std::array<double, 3>& x_m) {
  Parts out;
  out.r_m = std::sqrt(x_m[0] * x_m[0] + x_m[1] * x_m[1] + x_m[2] * x_m[2]);
  const std::array<double, 3> d{x_m[0] / out.r_m, x_m[1] / out.r_m, x_m[2] / out.r_m};
  const int samples = 2 * spec.solve.n_samples;
  const auto truth = stored_series(spec, surface, d, out.r_m, samples);
  const auto far = stored_series(spec, surface, d, 0, samples);
  // The radial model at d: R p = F + sum_i L_i(u) (R_i p_i - F) (kernels/pan/radial.hpp).
  const auto w = pan::radial_weights(spec.radii_m, out.r_m);
  const double u = 1.0 / out.r_m;
  std::vector<double> radial = far;
  const std::size_t m = spec.radii_m.size();
  for (int k = 0; k < w.count; ++k) {
    const std::size_t value = static_cast<std::size_t>(w.first + k);  // value v is radius v - 1
    const double l = w.near[static_cast<std::size_t>(k)] / u;
    if (l == 0 || value < 1 || value > m) continue;
    const auto at_radius = stored_series(spec, surface, d, spec.radii_m[value - 1], samples);
    for (std::size_t n = 0; n < radial.size(); ++n) radial[n] += l * (at_radius[n] - far[n]);
  }
  out.radial = jobs::far_field_miss(radial, truth, 0.0);
  // Between directions, at infinity and at R.
  const pan::DirectionWeights dw = mesh.locate(d);
  std::vector<double> far_sum(far.size(), 0.0), here_sum(far.size(), 0.0);
  for (int k = 0; k < dw.count; ++k) {
    const auto v = mesh.direction(static_cast<std::size_t>(dw.vertex[static_cast<std::size_t>(k)]));
    const double wk = dw.weight[static_cast<std::size_t>(k)];
    const auto f = stored_series(spec, surface, v, 0, samples), h = stored_series(spec, surface, v, out.r_m, samples);
    for (std::size_t n = 0; n < far.size(); ++n) {
      far_sum[n] += wk * f[n];
      here_sum[n] += wk * h[n];
    }
  }
  out.dir_far = jobs::far_field_miss(far_sum, far, 0.0);
  out.dir_here = jobs::far_field_miss(here_sum, truth, 0.0);
  return out;
}

int study(mpi::Session& session, int argc, char** argv) {
  CLI::App app{"clatter-pan-direction-study: adaptive against uniform direction sets (issue 32)"};
  analysis::PanStudyOptions options;
  std::vector<int> fields{1};
  double tolerance = 0.02;
  int levels = 3, tests = 256;
  std::vector<std::vector<double>> listeners_m;
  options.add_to(app);
  app.add_option("--point", listeners_m, "split the error at this listener x,y,z [m] into its parts")->delimiter(',');
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
  if (session.is_root())
    std::printf(listeners_m.empty() ? "field,set,directions,splits,far_fields,median_pct,p90_pct,worst_pct,above_5pct\n"
                                    : "field,directions,r_m,x,y,z,radial_pct,dir_far_pct,dir_here_pct\n");
  auto hook = [&](std::size_t fi, const kernels::fdtd::SurfaceField& surface) {
    const auto refined = jobs::refine_directions(spec, 0, surface, tolerance, levels, 5000);
    if (!listeners_m.empty()) {
      for (const auto& x : listeners_m) {
        const Parts e = error_parts(spec, surface, refined.mesh, {x.at(0), x.at(1), x.at(2)});
        std::printf("%d,%zu,%.3f,%.3f,%.3f,%.3f,%.2f,%.2f,%.2f\n", s.fields[fi], refined.mesh.size(), e.r_m, x[0] / e.r_m,
                    x[1] / e.r_m, x[2] / e.r_m, 100 * e.radial, 100 * e.dir_far, 100 * e.dir_here);
      }
      std::fflush(stdout);
      return;
    }
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
