// `clatter-bank modal-samples`: the adaptive sampling of the ellipsoid patch (003 §5.3,
// kernels/modal/patch_sampling.hpp) driven by the FEM itself. Each candidate ellipsoid is solved
// on a coarse mesh (mesh.coarse_edge_m) for its first few modes; its features are the frequency
// ratios f_2/f_1 .. f_{F+1}/f_1. Ratios, not frequencies: the synthesizer matches f_1 exactly by
// equi-frequency scaling (003 §5.4), so what a nearest proxy gets wrong is the shape of the
// spectrum above it. Candidates of a level are dealt round-robin to the ranks (each solves on its
// own); the result is a [patch] table to paste into a modal config.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>

#include "core/errors.hpp"
#include "banks/modal/modal_samples.hpp"
#include "banks/modal/modal_fem.hpp"
#include "banks/modal/modal_job.hpp"
#include "banks/modal/modal_solve.hpp"
#include "banks/modal/modal_spec.hpp"
#include "cli/run_options.hpp"
#include "kernels/modal/patch_sampling.hpp"
#include "mpi/collectives.hpp"
#include "mpi/comm.hpp"
#include "petsc/session.hpp"

namespace clatter::jobs {
namespace {

struct SamplesOptions {
  kernels::modal::PatchSamplingSettings sampling;
  int features = 4;
  std::string out = "samples.toml";
};

// f_2/f_1 .. f_{n+1}/f_1 of one ellipsoid on the coarse mesh (this rank alone).
std::vector<double> frequency_ratios(const ModalSpec& spec, const kernels::modal::Axes& axes, int n) {
  const FirstModeEstimate coarse = estimate_first_mode(MPI_COMM_SELF, spec, axes);  // the job's own
  const auto reference = reference_fields(coarse.model.layout, coarse.mesh.mesh, axes);
  // The bank's solve settings; only the range grows here, until the solve holds n + 1 modes.
  model::ModalSolveSettings settings = spec.header.solve;
  for (settings.f_max_multiple = 1.5;; settings.f_max_multiple *= 1.5) {
    const ModeSet set = solve_modes(coarse.model, reference, coarse.lambda1, settings);
    if (static_cast<int>(set.lambdas.size()) > n) {
      std::vector<double> ratios;
      for (int k = 1; k <= n; ++k) ratios.push_back(std::sqrt(set.lambdas[static_cast<std::size_t>(k)] / set.lambdas[0]));
      return ratios;
    }
  }
}

kernels::modal::FeatureBatch feature_batch(MPI_Comm world, const ModalSpec& spec, int n) {
  return [world, &spec, n](const std::vector<kernels::modal::Axes>& points) {
    const int rank = mpi::rank(world), size = mpi::size(world);
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<double> mine(points.size() * static_cast<std::size_t>(n), 0.0);
    mpi::agree(world, [&] {
      for (std::size_t i = static_cast<std::size_t>(rank); i < points.size(); i += static_cast<std::size_t>(size)) {
        std::vector<double> r;
        try {
          r = frequency_ratios(spec, points[i], n);
        } catch (const std::exception& e) {
          throw std::runtime_error(fmt::format("modal-samples: ellipsoid ({:.6f}, {:.6f}, {:.6f}): {}", points[i][0],
                                               points[i][1], points[i][2], e.what()));
        }
        std::copy(r.begin(), r.end(), mine.begin() + static_cast<long>(i * static_cast<std::size_t>(n)));
      }
    });
    // Each value comes from one rank, the others add zeros: the sum is exact.
    const std::vector<double> all = mpi::all_reduce_sum(world, mine);
    spdlog::info("modal-samples: {} ellipsoids solved in {:.1f} s", points.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::vector<std::vector<double>> out;
    for (std::size_t i = 0; i < points.size(); ++i)
      out.emplace_back(all.begin() + static_cast<long>(i * static_cast<std::size_t>(n)),
                       all.begin() + static_cast<long>((i + 1) * static_cast<std::size_t>(n)));
    return out;
  };
}

std::string patch_table(const kernels::modal::PatchSampling& s, const SamplesOptions& o) {
  std::string out = fmt::format(
      "# clatter-bank modal-samples: {} ellipsoids; features f_2/f_1 .. f_{}/f_1 on the coarse mesh; every edge of the\n"
      "# final triangulation changes them by at most {:.4f} (tolerance {}, {} edges over it at max_level {}).\n"
      "[patch]\nmin_ratio = {}\nsamples = [\n",
      s.samples.size(), o.features + 1, s.worst_change, o.sampling.tolerance, s.edges_over_tolerance,
      o.sampling.max_level, o.sampling.min_ratio);
  for (const auto& a : s.samples) out += fmt::format("  [{:.17g}, {:.17g}, {:.17g}],\n", a[0], a[1], a[2]);
  return out + "]\n";
}

}  // namespace

Command add_modal_samples_command(CLI::App& parent) {
  auto* app = parent.add_subcommand("modal-samples", "sample the ellipsoid patch adaptively for a modal bank (coarse "
                                                     "FEM solves; writes a [patch] table, docs/modal.md)");
  auto options = std::make_shared<ConfigOptions>();
  auto samples = std::make_shared<SamplesOptions>();
  add_config_options(*app, *options);
  add_out_option(*app, samples->out, "output TOML [patch] table");
  app->add_option("--tolerance", samples->sampling.tolerance, "largest relative change of a feature along an edge")
      ->capture_default_str();
  app->add_option("--initial-divisions", samples->sampling.initial_divisions, "level-0 grid: n^2 triangles")
      ->capture_default_str();
  app->add_option("--max-level", samples->sampling.max_level, "refinement levels")->capture_default_str();
  app->add_option("--features", samples->features, "frequency ratios compared")->capture_default_str()
      ->check(CLI::Range(1, 20));
  return {app, [options, samples](const RunContext& context) -> int {
            const auto config = job_config(context.world, modal_schema(), *options);
            if (!config) return kExitOk;
            ModalSpec spec;
            mpi::agree(context.world, [&] {
              io::Config sampling = *config;  // the samples are what this command makes: any will do here
              sampling.set("patch.samples=[[0.5773502691896258, 0.5773502691896258, 0.5773502691896258]]");
              spec = make_modal_spec(sampling);
            });
            samples->sampling.min_ratio = spec.header.min_ratio;
            const petsc::Session petsc(context.world);
            kernels::modal::PatchSampling result;
            mpi::agree(context.world, [&] {
              try {
                result = kernels::modal::sample_patch(samples->sampling,
                                                      feature_batch(context.world, spec, samples->features));
              } catch (const std::invalid_argument& e) {
                throw InputError(fmt::format("modal-samples: {}", e.what()));
              }
            });
            if (context.is_root) {
              std::ofstream out(samples->out);
              out << patch_table(result, *samples);
              if (!out) throw InputError(fmt::format("-o {}: cannot write the file", samples->out));
              spdlog::info("modal-samples: {} ellipsoids, worst change {:.4f}, written to {}", result.samples.size(),
                           result.worst_change, samples->out);
            }
            return kExitOk;
          }};
}

}  // namespace clatter::jobs
