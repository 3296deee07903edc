// clatter-sim: a rigid-body simulation (Bullet) of meshes, a pre-fractured plate or a rock pile,
// written as a native Clatter scene of contact and fracture impulses (docs/synth.md).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>

#include "core/cleanup.hpp"
#include "core/errors.hpp"
#include "core/stage_log.hpp"
#include "io/config.hpp"
#include "io/linked_libraries.hpp"
#include "io/scene.hpp"
#include "io/text_file.hpp"
#include "sim/simulate.hpp"

using namespace clatter;

namespace {


struct Options {
  std::string config_path, out = "scene.json";
  std::vector<std::string> sets;
  bool print_config = false, quiet = false, log_view = false;
};

void simulate_and_write(const Options& o, const io::Config& config) {
  Stage total("clatter-sim");
  const auto t0 = std::chrono::steady_clock::now();
  const double dt = config.real("sim.dt_s");
  std::printf("clatter-sim: %s: %.4g s at a fixed step of %.4g ms (%.4g kHz)\n", o.config_path.empty() ? "built-in config" : o.config_path.c_str(),
              config.real("sim.duration_s"), dt * 1e3, 1e-3 / dt);
  std::fflush(stdout);
  // Before the run, not after it: a file where the meshes go would fail the write.
  const std::string mesh_folder = io::scene_mesh_folder(o.out);
  sim::SimStats stats;
  auto progress = [&](std::size_t done, std::size_t all) {
    if (o.quiet) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("clatter-sim: %3.0f %% (%zu/%zu steps), %.1f s, ETA %.1f s\n", 100.0 * static_cast<double>(done) / static_cast<double>(all),
                done, all, s, s * static_cast<double>(all - done) / static_cast<double>(done));
    std::fflush(stdout);
  };
  auto on_fracture = [&](const io::SceneFracture& r) {
    if (o.quiet) return;
    std::printf("clatter-sim: %.4f s: body %d broke into %zu pieces: sigma_1 %.3g MPa (strength %.3g), E_S %.4g J, E_F %.4g J "
                "(A_F %.4g m^2 at G_c %.4g J/m^2), Delta E_K %.4g J, tau %.3g us (%zu tetrahedra)\n",
                r.t_s, r.body, r.pieces.size(), r.max_principal_pa * 1e-6, r.strength_pa * 1e-6, r.strain_energy_j, r.fracture_energy_j,
                r.fracture_area_m2, r.toughness_j_m2, r.kinetic_energy_gained_j, r.tau_s * 1e6, r.tets);
    std::fflush(stdout);
  };
  const io::Scene scene = sim::simulate(config, o.config_path, &stats, progress, on_fracture);
  const nlohmann::json generator = {
      {"program", "clatter-sim"}, {"version", io::version_text("clatter-sim")}, {"time_step_s", dt}, {"config", config.to_toml()}};
  {
    Stage stage("write");
    io::write_scene(scene, o.out, generator.dump());
  }
  std::printf("clatter-sim: wrote %s and its %zu objects' meshes in %s/ (%s), %zu events: %zu impacts, %zu sustained contacts, %zu fracture impulses "
              "(from %zu contact-point steps); %zu steps in %.2f s (%.3g steps/s)\n",
              o.out.c_str(), scene.objects.size(), mesh_folder.c_str(),
              stats.fracture_s >= 0 ? fmt::format("first fracture at {:.4f} s", stats.fracture_s).c_str() : "no fracture",
              scene.events.size(), stats.impacts, stats.sustained, stats.fracture_events, stats.contact_samples, stats.steps,
              stats.wall_s, static_cast<double>(stats.steps) / stats.wall_s);
  const sim::FractureStats& f = stats.fracture;
  if (f.factorizations) {
    std::size_t pieces = 0;
    for (const auto& r : scene.fractures) pieces += r.pieces.size();
    std::printf("clatter-sim: fracture (003 section 3): %zu fractures made %zu pieces (%zu more refused: E_S could not pay for two "
                "pieces), %zu steps' stress bounded by the energy the contacts took, %zu contact steps too weak to solve; %zu stress solves in %.3g s (%.3g ms each), "
                "%zu factorizations in %.3g s (largest %zu dofs), patterns %.3g s\n",
                f.fractures, pieces, f.refused, f.energy_bounded, f.skipped, f.stress_solves, f.solve_s, f.stress_solves ? 1e3 * f.solve_s / static_cast<double>(f.stress_solves) : 0.0,
                f.factorizations, f.factorize_s, f.largest_dofs, f.pattern_s);
  }
}

int run(const Options& o) {
  io::Config config(sim::sim_schema());
  if (!o.config_path.empty()) config.merge_toml(io::read_text_file(o.config_path), o.config_path);
  for (const auto& s : o.sets) config.set(s);
  if (o.print_config) {
    std::fputs(config.to_toml().c_str(), stdout);
    return kExitOk;
  }
  simulate_and_write(o, config);
  if (o.log_view) std::fputs(format_stage_table(merge_stage_entries({stage_log().entries()}), 1).c_str(), stdout);
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"clatter-sim: simulates rigid bodies (Bullet) falling on a ground plane, bodies that break by their "
               "quasistatic stress (003 section 3: plate, slab), a Voronoi pre-fractured plate, or a pile of rocks, and writes their contact and fracture impulses as a Clatter "
               "scene for clatter-synth (docs/synth.md).\nExit codes: 0 done, 1 run-time failure, 2 bad input.",
               "clatter-sim"};
  app.set_version_flag("--version", io::version_text("clatter-sim"));
  Options o;
  app.add_option("-c,--config", o.config_path, "TOML config (scenes/*.toml; default: the built-in config, see --print-config)");
  app.add_option("--set", o.sets, "override one config key, e.g. --set plate.pieces=60 (repeatable)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
  app.add_flag("--print-config", o.print_config, "print the effective config as TOML and exit");
  app.add_option("-o,--out", o.out, "output scene (JSON)")->capture_default_str();
  app.add_flag("-q,--quiet", o.quiet, "no progress lines");
  app.add_flag("--log-view", o.log_view, "print the stage-timing table at the end");
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "clatter-sim: error: %s (see clatter-sim --help)\n", e.what());
    return kExitInputError;
  }
  try {
    return run(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "clatter-sim: error: %s\n", e.what());
    remove_registered_temporaries();
    return kExitInputError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clatter-sim: error: %s\n", e.what());
    remove_registered_temporaries();
    return kExitFailure;
  }
}
