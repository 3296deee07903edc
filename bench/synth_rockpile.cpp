// clatter-synth-bench: the paper's largest example at full size (Chadwick et al. 2012, "Rock pile
// (large)": 1000 rocks, 210,741 impulses over 6 s, 192 s to synthesize there). A seeded generator
// makes a scene of that size in memory; the acceleration noise is rendered at 44.1 kHz on one
// core, REPEATS times; with a modal bank, the rocks' modes too; with a ground bank, the ground's
// sound at every rock-ground impact (then also the ground source alone, for its cost per impact).
// Prints the median wall time, impacts per second, the split between the stages of an impact
// (docs/benchmarks.md) and the peak resident memory.
// Usage: clatter-synth-bench BANK [REPEATS=5] [EVENTS=210741] [MODAL_BANK|-] [GROUND_BANK]
//        clatter-synth-bench --write-scene OUT.json [EVENTS=210741] [GROUND_BANK]
// The second form writes the scene as a scene file instead (its ground the bank's, as the first
// form renders it), for timing clatter-synth and the Python module on it (bench/python_vs_cli.py).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <memory>
#include <string>
#include <vector>

#include "bench/solid_ellipsoid.hpp"
#include "core/stage_log.hpp"
#include "synth/ground_source.hpp"
#include "synth/modal_source.hpp"
#include "io/scene.hpp"
#include "synth/render_scene.hpp"
#include "tests/unit/make_material.hpp"

using namespace clatter;

namespace {

io::Scene rock_pile(std::size_t n_objects, std::size_t n_events, double duration_s) {
  std::mt19937_64 rng(20121122);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  io::Scene s;
  s.path = "generated rock pile";
  s.materials["granite"] = clatter::test::damped(5e10, 0.2, 6.0, 1e-7);  // nu of the glass-class modal bank (docs/materials.md)
  s.materials["concrete"] = clatter::test::elastic(3e10, 0.2);
  s.ground_material = "concrete";
  const double pi = 3.14159265358979323846;
  for (std::size_t i = 0; i < n_objects; ++i) {
    const double a = 0.02 + 0.04 * u(rng), b = a * (0.5 + 0.5 * u(rng)), c = b * (0.4 + 0.6 * u(rng));
    s.objects.push_back(bench::solid_ellipsoid(static_cast<int>(i + 1), a, b, c, 2700, "granite"));
  }
  std::vector<double> times(n_events);
  for (double& t : times) t = duration_s * std::pow(u(rng), 1.5);  // a pile settling: dense early
  std::sort(times.begin(), times.end());
  for (std::size_t k = 0; k < n_events; ++k) {
    io::SceneEvent e;
    e.t_s = times[k];
    e.a = 1 + static_cast<int>(u(rng) * static_cast<double>(n_objects)) % static_cast<int>(n_objects);
    e.b = u(rng) < 0.3 ? 1 + (e.a % static_cast<int>(n_objects)) : 0;  // 30 % rock-rock
    const double angle = 2 * pi * u(rng);
    e.pose_a.position_m = {u(rng) - 0.5, u(rng) - 0.5, 0.05 + 0.3 * u(rng)};
    e.pose_a.orientation_wxyz = {std::cos(angle / 2), 0, std::sin(angle / 2), 0};
    e.pose_b = e.pose_a;
    e.pose_b.position_m[0] += 0.08;
    e.point_m = {e.pose_a.position_m[0] + 0.01, e.pose_a.position_m[1], e.pose_a.position_m[2] - 0.01};
    const double speed = 0.05 + 2.0 * u(rng) * std::exp(-e.t_s / 2);
    const double j = s.objects[static_cast<std::size_t>(e.a - 1)].mass_kg * speed * 1.5;
    e.impulse_n_s = {0.2 * j * (u(rng) - 0.5), 0.2 * j * (u(rng) - 0.5), j};
    e.normal_speed_m_s = speed;
    e.where = "event " + std::to_string(k);
    s.events.push_back(e);
  }
  s.listeners_m.push_back({0.0, 3.0, 1.5});
  s.duration_s = duration_s + 0.1;
  return s;
}

// The ground bank's material for the pile's floor: its concrete (else its first material), whose
// moduli the scene then takes, so the bank's series hold for it.
void use_bank_ground(io::Scene& scene, const synth::GroundSource& ground) {
  const auto& materials = ground.bank().materials;
  const model::GroundMaterial* m = &materials.front();
  for (const auto& candidate : materials)
    if (candidate.name == "concrete") m = &candidate;
  scene.ground_material = m->name;
  scene.materials[m->name] = *m;  // its moduli and density (a GroundMaterial is a Material)
}

struct Timing {
  double median_s = 0, min_s = 0, max_s = 0;
  synth::RenderStats stats;
};

Timing time_renders(const io::Scene& scene, const std::vector<synth::SoundSource*>& sources, int repeats, const char* label) {
  std::vector<double> walls;
  Timing t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto out = synth::render_scene(scene, sources, {}, &t.stats);
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::printf("%s run %d: %.3f s (%zu impacts, %zu samples)\n", label, r + 1, walls.back(), t.stats.impacts, out[0][0].size());
  }
  std::sort(walls.begin(), walls.end());
  t.median_s = walls[walls.size() / 2], t.min_s = walls.front(), t.max_s = walls.back();
  return t;
}

// A source that adds nothing: the event loop's own time (Hertz times, frames, stages).
class Silent : public synth::SoundSource {
 public:
  std::string name() const override { return "silent"; }
  void add(const synth::Impact&, const std::vector<Vec3>&, int, std::vector<std::vector<double>>&) override {}
};

// The ground source alone over the same scene, less the loop alone: its cost per ground impact
// and listener.
void report_ground(const io::Scene& scene, synth::GroundSource& ground, int repeats) {
  Silent silent;
  const Timing loop = time_renders(scene, {&silent}, repeats, "loop alone");
  const Timing alone = time_renders(scene, {&ground}, repeats, "ground alone");
  const synth::GroundStats& g = ground.stats();
  const double pairs = static_cast<double>(g.impacts * scene.listeners_m.size());
  std::printf("  ground: %zu ground impacts on '%s' x %zu listener(s); eta raised to one sample %zu, clamped below %zu, above %zu; "
              "elevation clamped %zu\n",
              g.impacts, ground.medium().material->name.c_str(), scene.listeners_m.size(), g.eta_below_sample, g.eta_below_grid,
              g.eta_above_grid, g.elevation_outside);
  std::printf("  ground alone: median %.3f s of %d (min %.3f, max %.3f); the loop alone (no source) %.3f s: %.2f us per ground "
              "impact and listener\n",
              alone.median_s, repeats, alone.min_s, alone.max_s, loop.median_s,
              1e6 * (alone.median_s - loop.median_s) / std::max(pairs, 1.0));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: clatter-synth-bench BANK [REPEATS=5] [EVENTS=210741] [MODAL_BANK|-] [GROUND_BANK]\n");
    return 2;
  }
  if (std::string(argv[1]) == "--write-scene") {
    if (argc < 3) return std::fprintf(stderr, "usage: clatter-synth-bench --write-scene OUT.json [EVENTS] [GROUND_BANK]\n"), 2;
    io::Scene scene = rock_pile(1000, argc > 3 ? static_cast<std::size_t>(std::atol(argv[3])) : 210741, 6.0);
    if (argc > 4) use_bank_ground(scene, synth::GroundSource(argv[4]));
    io::write_scene(scene, argv[2], R"({"program": "clatter-synth-bench --write-scene"})");
    std::printf("wrote %s: %zu objects, %zu events\n", argv[2], scene.objects.size(), scene.events.size());
    return 0;
  }
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  const std::size_t events = argc > 3 ? static_cast<std::size_t>(std::atol(argv[3])) : 210741;
  io::Scene scene = rock_pile(1000, events, 6.0);
  const auto t_load = std::chrono::steady_clock::now();
  synth::PanSource pan(argv[1]);
  std::unique_ptr<synth::ModalSource> modal;
  std::unique_ptr<synth::GroundSource> ground;
  if (argc > 4 && std::string(argv[4]) != "-") modal = std::make_unique<synth::ModalSource>(std::vector<std::string>{argv[4]});
  if (argc > 5) ground = std::make_unique<synth::GroundSource>(argv[5]);
  std::vector<synth::SoundSource*> sources{&pan};
  if (modal) sources.push_back(modal.get());
  if (ground) {
    use_bank_ground(scene, *ground);
    sources.push_back(ground.get());
  }
  const double load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_load).count();
  const Timing all = time_renders(scene, sources, repeats, "all");
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("rock pile: 1000 objects, %zu events -> %zu impacts, 6.1 s at 44.1 kHz, 1 core\n", events, all.stats.impacts);
  std::printf("  bank load: %.3f s (%s%s%s%s%s)\n", load_s, argv[1], modal ? " and " : "", modal ? argv[4] : "", ground ? " and " : "",
              ground ? argv[5] : "");
  if (modal)
    std::printf("  modal: %zu modes rendered, %zu above 20 kHz skipped; %zu excitations, %.3g mode-samples\n", modal->stats().modes,
                modal->stats().skipped_high, modal->stats().excitations, static_cast<double>(modal->stats().resonators.mode_samples));
  std::printf("  render (%s): median %.3f s of %d (min %.3f, max %.3f): %.3g impacts/s; %.0fx faster than the paper's 192 s\n",
              ground ? (modal ? "PAN + modal + ground" : "PAN + ground") : (modal ? "PAN + modal" : "PAN"), all.median_s, repeats,
              all.min_s, all.max_s, static_cast<double>(all.stats.impacts) / all.median_s, 192.0 / all.median_s);
  std::printf("  peak resident memory: %.1f MiB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
  std::printf("  stages, summed over the %d runs:\n", repeats);
  std::fputs(format_stage_table(merge_stage_entries({stage_log().entries()}), 1).c_str(), stdout);
  if (ground) report_ground(scene, *ground, repeats);
  return 0;
}
