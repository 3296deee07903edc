// clatter-pan-held-out-study: issue 32's acceptance measure for one proxy at any resolution. The
// proxy is built as a bank task builds it (each field's adaptive directions, the fit), written and
// read back through the bank format, and evaluated at held-out points: random directions (no vertex
// of any set, with probability one) at radii between and beyond the stored ones, against the same
// solve's raw field heard there through the Kirchhoff surface (validated against the exact sphere,
// docs/fdtd.md). Fields the proxy does not radiate (below 1 % of its strongest field's energy at
// these points, a rotation field taken per unit surface acceleration: times 1/A) are listed and
// excluded. One CSV row per field.
//
//   mpiexec -n 2 clatter-pan-held-out-study [-c configs/pan.toml] --proxy 0.2625,0.12
//       [--radii 0.77,1.1,1.75,2.5,3] [--directions 8] [--seed 3] [--set key=value ...]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "analysis/pan_study_options.hpp"
#include "banks/pan/pan_job.hpp"
#include "banks/pan/pan_spec.hpp"
#include "io/pan_bank.hpp"
#include "kernels/pan/field.hpp"
#include "mpi/session.hpp"

namespace {

using namespace clatter;

int study(mpi::Session& session, int argc, char** argv) {
  CLI::App app{"clatter-pan-held-out-study: a proxy's bank against its raw field at held-out points (issue 32)"};
  analysis::PanStudyOptions options;
  std::string bank_path = "held_out_study.h5";
  std::vector<double> radii{0.77, 1.1, 1.75, 2.5, 3.0};
  int directions = 8;
  unsigned seed = 3;
  options.add_to(app);
  app.add_option("--radii", radii, "held-out radii [m]")->delimiter(',');
  app.add_option("--directions", directions, "random held-out directions");
  app.add_option("--seed", seed, "of the random directions");
  app.add_option("--bank", bank_path, "where the one-proxy bank is written and read back");
  CLI11_PARSE(app, argc, argv);
  const io::Config config = options.config();
  const auto spec = jobs::make_pan_spec(config);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::array<double, 3>> points;
  const double step = spec.solve.problem.c_m_s * spec.solve.problem.dt_s;
  for (int i = 0; i < directions; ++i) {
    std::array<double, 3> d{u(rng), u(rng), u(rng)};
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double r : radii) {
      const double whole = std::round(r / step) * step;  // the raw series on PAN samples
      points.push_back({whole * d[0] / n, whole * d[1] / n, whole * d[2] / n});
    }
  }
  auto result = jobs::build_proxy(session.world(), spec, 0, points, 0.0);
  if (!session.is_root()) return 0;
  model::PanBank bank;
  bank.header = jobs::pan_header(spec);
  bank.proxies.push_back(result.proxy);
  io::write_pan_bank(bank_path, bank, "clatter-pan-held-out-study", config.to_toml(), session.size());
  bank = io::read_pan_bank(bank_path);
  kernels::pan::check_direction_sets(bank);
  const std::size_t ns = static_cast<std::size_t>(spec.solve.n_samples);
  std::vector<double> energy(spec.solve.fields.size(), 0.0);
  for (std::size_t f = 0; f < energy.size(); ++f) {
    for (std::size_t k = 0; k < points.size() * ns; ++k) energy[f] += double{result.extra_series[f][k]} * result.extra_series[f][k];
    if (spec.solve.fields[f] > 3) energy[f] /= spec.a_m * spec.a_m;
  }
  const double strongest = *std::max_element(energy.begin(), energy.end());
  // Besides the relative error at each point, the error against max(the point's L2, a tenth of
  // the field's largest L2 at that radius): the refinement's floor (pan_job.hpp refine_directions),
  // which tells a miss in a direction the field hardly radiates from one where it radiates.
  std::printf("field,directions,energy_fraction,radiated,median_pct,p90_pct,worst_pct,points_above_5pct,points,"
              "floored_worst_pct,floored_above_5pct\n");
  for (std::size_t f = 0; f < energy.size(); ++f) {
    const int field = spec.solve.fields[f];
    std::vector<double> errors, l2(points.size(), 0.0), radius_peak(radii.size(), 0.0);
    for (std::size_t l = 0; l < points.size(); ++l) {
      errors.push_back(jobs::held_out_error(spec, bank.header, bank.proxies[0], field, points[l],
                                            result.extra_series[f].data() + l * ns));
      for (std::size_t k = 0; k < ns; ++k) l2[l] += double{result.extra_series[f][l * ns + k]} * result.extra_series[f][l * ns + k];
      l2[l] = std::sqrt(l2[l]);
      radius_peak[l % radii.size()] = std::max(radius_peak[l % radii.size()], l2[l]);
    }
    int above = 0, floored_above = 0;
    double floored_worst = 0;
    for (std::size_t l = 0; l < points.size(); ++l) {
      above += errors[l] > 0.05;
      const double floored = errors[l] * l2[l] / std::max(l2[l], 0.1 * radius_peak[l % radii.size()]);
      floored_worst = std::max(floored_worst, floored);
      floored_above += floored > 0.05;
    }
    std::printf("%d,%zu,%.4f,%s,%.2f,%.2f,%.2f,%d,%zu,%.2f,%d\n", field, bank.proxies[0].field(field).terms.size(),
                energy[f] / strongest, energy[f] >= 0.01 * strongest ? "yes" : "no (excluded)", 100 * analysis::percentile(errors, 0.5),
                100 * analysis::percentile(errors, 0.9), 100 * analysis::percentile(errors, 1.0), above, errors.size(), 100 * floored_worst,
                floored_above);
  }
  std::printf("bank: %s, %.3f MB\n", bank_path.c_str(), static_cast<double>(std::filesystem::file_size(bank_path)) / 1e6);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return clatter::mpi::run(argc, argv, "clatter-pan-held-out-study",
                           [&](clatter::mpi::Session& session) { return study(session, argc, argv); });
}
