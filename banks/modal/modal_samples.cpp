// `clatter-bank modal-samples`: the adaptive sampling of the ellipsoid patch (003 §5.3,
// kernels/modal/patch_sampling.hpp) driven by the FEM itself. Each candidate ellipsoid is solved
// on a coarse mesh (mesh.coarse_edge_m) for its first few modes; its features are the frequency
// ratios f_2/f_1 .. f_{F+1}/f_1. Ratios, not frequencies: the synthesizer matches f_1 exactly by
// equi-frequency scaling (003 §5.4), so what a nearest proxy gets wrong is the shape of the
// spectrum above it. Candidates of a level are dealt round-robin to the ranks (each solves on its
// own); the result is a [patch] table to paste into a modal config.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

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
#include "petsc/eigen.hpp"
#include "petsc/inertia.hpp"
#include "petsc/session.hpp"

namespace clatter::jobs {
namespace {

// The default tolerance is the one the default sample set meets (docs/modal.md "Sampling the
// patch": 77 entries; 0.3 takes 120, 0.1 more than 434).
kernels::modal::PatchSamplingSettings default_sampling() {
  kernels::modal::PatchSamplingSettings s;
  s.tolerance = 0.4;
  return s;
}

struct SamplesOptions {
  kernels::modal::PatchSamplingSettings sampling = default_sampling();
  int features = 4;
  std::string out = "samples.toml";
  bool resume = false;
};

// The solves so far, in OUT.solves beside the output: one line per ellipsoid (its axes and
// features, %.17g: they read back to the bit), appended by rank 0 after each level, under a first
// line naming what the features depend on. --resume reads it back and solves only the rest, so a
// run stopped at any level, or rerun with another --tolerance or --max-level, pays only for new
// candidates. A key is the axes' exact bits: the sampler makes the same points from the same
// settings.
class SolveCache {
 public:
  SolveCache(const ModalSpec& spec, const SamplesOptions& o) : path_(o.out + ".solves") {
    const auto& h = spec.header;
    const auto& m = h.material;
    identity_ = fmt::format(
        "# clatter-bank modal-samples solves: features {}; material {} rho {:.17g} E {:.17g} nu {:.17g}; coarse_edge_m "
        "{:.17g}, coarse cap {:.17g}, layered below {:.17g}, coarse layers {}; solver tolerance {:.17g}",
        o.features, m.name, m.rho_kg_m3, m.youngs_pa, m.poisson, h.coarse_edge_m, h.coarse_elements_through_thickness,
        h.layered_below_ratio, h.coarse_layers, h.solve.tolerance);
  }

  // Rank 0: the cache read (--resume) or started; an error naming the file otherwise.
  void open(bool resume, int features) {
    std::ifstream in(path_);
    if (in && !resume)
      throw InputError(fmt::format("{}: the solves of an earlier run are there: --resume reuses them (or remove the file)",
                                   path_));
    if (in) {
      std::string line;
      std::getline(in, line);
      if (line != identity_)
        throw InputError(fmt::format("{}: made with other settings than this run's:\n  file: {}\n  run:  {}", path_, line,
                                     identity_));
      for (int number = 2; std::getline(in, line); ++number) {
        std::istringstream fields(line);
        kernels::modal::Axes axes{};
        std::vector<double> values(static_cast<std::size_t>(features));
        for (double& x : axes) fields >> x;
        for (double& x : values) fields >> x;
        if (!fields) throw InputError(fmt::format("{}:{}: not 3 axes and {} features", path_, number, features));
        solved_[axes] = values;
      }
      spdlog::info("modal-samples: {} solves read from {}", solved_.size(), path_);
      return;
    }
    std::ofstream out(path_);
    out << identity_ << "\n";
    if (!out) throw InputError(fmt::format("{}: cannot write the file", path_));
  }

  const std::map<kernels::modal::Axes, std::vector<double>>& solved() const { return solved_; }

  void append(const kernels::modal::Axes& axes, const std::vector<double>& features) {
    std::ofstream out(path_, std::ios::app);
    out << fmt::format("{:.17g} {:.17g} {:.17g}", axes[0], axes[1], axes[2]);
    for (double f : features) out << fmt::format(" {:.17g}", f);
    out << "\n";
    if (!out) throw std::runtime_error(path_ + ": cannot append to the file");
    solved_[axes] = features;
  }

 private:
  std::string path_, identity_;
  std::map<kernels::modal::Axes, std::vector<double>> solved_;  // rank 0's copy
};

// f_2/f_1 .. f_{n+1}/f_1 of one ellipsoid on the coarse mesh (this rank alone).
std::vector<double> frequency_ratios(const ModalSpec& spec, const kernels::modal::Axes& axes, int n) {
  const FirstModeEstimate coarse = estimate_first_mode(MPI_COMM_SELF, spec, axes);  // the job's own
  const auto ratios_of = [n](const std::vector<double>& lambdas) {
    std::vector<double> ratios;
    for (int k = 1; k <= n; ++k) ratios.push_back(std::sqrt(lambdas[static_cast<std::size_t>(k)] / lambdas[0]));
    return ratios;
  };
  // The lowest modes by one shift-and-invert solve just below the rigid motions' 0 (the rigid
  // motions deflated), a few more than n + 1 so that a multiplet at the (n+1)-th is found whole,
  // then proved complete by Sylvester's inertia: as many eigenvalues below the (n+1)-th (and its
  // multiplet) as found. Slicing with a widening range did the same at up to 5 solves of growing
  // intervals (a rod's f_5 / f_1 is 5.4: ranges 1.5, 2.25, ... 7.6 f_1); it stays the fallback.
  petsc::LowestSettings lowest;
  lowest.count = n + 1 + 4;
  lowest.tolerance = spec.header.solve.tolerance;
  lowest.shift = -coarse.lambda1 / 100;
  try {
    const auto solution = petsc::lowest_eigenpairs(coarse.model.K, coarse.model.M, lowest, coarse.model.rigid);
    const double top = solution.lambdas.at(static_cast<std::size_t>(n)) * (1 + spec.header.solve.cluster_gap);
    const auto found = std::count_if(solution.lambdas.begin(), solution.lambdas.end(), [top](double l) { return l < top; });
    if (static_cast<std::size_t>(found) < solution.lambdas.size() &&
        petsc::eigenvalues_below(coarse.model.K, coarse.model.M, top) - 6 == found)
      return ratios_of(solution.lambdas);
  } catch (const std::runtime_error&) {  // fewer pairs converged: the slicing below decides
  }
  const auto reference = reference_fields(coarse.model.layout, coarse.mesh.mesh, axes);
  model::ModalSolveSettings settings = spec.header.solve;
  for (settings.f_max_multiple = 1.5;; settings.f_max_multiple *= 1.5) {
    const ModeSet set = solve_modes(coarse.model, reference, coarse.lambda1, settings);
    if (static_cast<int>(set.lambdas.size()) > n) return ratios_of(set.lambdas);
  }
}

kernels::modal::FeatureBatch feature_batch(MPI_Comm world, const ModalSpec& spec, int n, SolveCache& cache) {
  return [world, &spec, n, &cache](const std::vector<kernels::modal::Axes>& points) {
    const int rank = mpi::rank(world), size = mpi::size(world);
    const auto t0 = std::chrono::steady_clock::now();
    // The points the cache does not hold (rank 0 knows; every rank gets the list).
    std::vector<double> known(points.size(), 0.0);
    if (rank == 0)
      for (std::size_t i = 0; i < points.size(); ++i) known[i] = cache.solved().count(points[i]) ? 1.0 : 0.0;
    known = mpi::all_reduce_sum(world, known);
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (known[i] == 0) todo.push_back(i);
    std::vector<double> mine(points.size() * static_cast<std::size_t>(n), 0.0);
    mpi::agree(world, [&] {
      for (std::size_t j = static_cast<std::size_t>(rank); j < todo.size(); j += static_cast<std::size_t>(size)) {
        const std::size_t i = todo[j];
        std::vector<double> r;
        const auto t_point = std::chrono::steady_clock::now();
        try {
          r = frequency_ratios(spec, points[i], n);
          // Progress per candidate (rank 0's; every rank's with --log-all-ranks): which ones cost.
          spdlog::info("modal-samples: ({:.4f}, {:.4f}, {:.4f}) a/c {:.4f}: f_2/f_1 {:.4f} in {:.1f} s (rank {}, {} of {})",
                       points[i][0], points[i][1], points[i][2], points[i][0] / points[i][2], r.front(),
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - t_point).count(), rank, j + 1,
                       todo.size());
        } catch (const std::exception& e) {
          throw std::runtime_error(fmt::format("modal-samples: ellipsoid ({:.6f}, {:.6f}, {:.6f}): {}", points[i][0],
                                               points[i][1], points[i][2], e.what()));
        }
        std::copy(r.begin(), r.end(), mine.begin() + static_cast<long>(i * static_cast<std::size_t>(n)));
      }
    });
    // A cached point's features come from rank 0's cache, a solved one's from its rank; the
    // others add zeros, so the sum is exact and every rank gets every point.
    if (rank == 0)
      for (std::size_t i = 0; i < points.size(); ++i)
        if (known[i] != 0) {
          const auto& f = cache.solved().at(points[i]);
          std::copy(f.begin(), f.end(), mine.begin() + static_cast<long>(i * static_cast<std::size_t>(n)));
        }
    const std::vector<double> all = mpi::all_reduce_sum(world, mine);
    std::vector<std::vector<double>> out;
    for (std::size_t i = 0; i < points.size(); ++i) {
      out.emplace_back(all.begin() + static_cast<long>(i * static_cast<std::size_t>(n)),
                       all.begin() + static_cast<long>((i + 1) * static_cast<std::size_t>(n)));
      if (rank == 0 && known[i] == 0) cache.append(points[i], out.back());
    }
    spdlog::info("modal-samples: {} ellipsoids ({} solved, {} from the cache) in {:.1f} s", points.size(), todo.size(),
                 points.size() - todo.size(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    return out;
  };
}

std::string patch_table(const kernels::modal::PatchSampling& s, const SamplesOptions& o) {
  std::string out = fmt::format(
      "# clatter-bank modal-samples: {} ellipsoids; features f_2/f_1 .. f_{}/f_1 on the coarse mesh; every edge of the\n"
      "# final triangulation changes them by at most {:.4f} (tolerance {}, {} edges over it at max_level {}).\n"
      "[patch]\nmin_ratio = {}\ncigar_ratio = {}\nsamples = [\n",
      s.samples.size(), o.features + 1, s.worst_change, o.sampling.tolerance, s.edges_over_tolerance,
      o.sampling.max_level, o.sampling.corners.min_ratio, o.sampling.corners.cigar_ratio);
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
  app->add_flag("--resume", samples->resume, "reuse the solves of an earlier run (OUT.solves) and solve only the rest");
  return {app, [options, samples](const RunContext& context) -> int {
            const auto config = job_config(context.world, modal_schema(), *options);
            if (!config) return kExitOk;
            ModalSpec spec;
            mpi::agree(context.world, [&] {
              io::Config sampling = *config;  // the samples are what this command makes: any will do here
              sampling.set("patch.samples=[[0.5773502691896258, 0.5773502691896258, 0.5773502691896258]]");
              spec = make_modal_spec(sampling);
            });
            samples->sampling.corners = {spec.header.min_ratio, spec.header.cigar_ratio};
            SolveCache cache(spec, *samples);
            mpi::agree(context.world, [&] {
              if (context.is_root) cache.open(samples->resume, samples->features);
            });
            const petsc::Session petsc(context.world);
            kernels::modal::PatchSampling result;
            mpi::agree(context.world, [&] {
              try {
                result = kernels::modal::sample_patch(samples->sampling,
                                                      feature_batch(context.world, spec, samples->features, cache));
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
