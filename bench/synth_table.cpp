// clatter-synth-table-bench: modal sound at the size of the paper's table setting (Zheng & James
// 2010, Table 3: 328 objects, 4046 modes, 5 s; 20 min of serial audio synthesis there). A seeded
// generator makes the scene in memory: glass shards of random shapes and sizes, each struck
// about 20 times (denser early) after a fracture impulse at its creation; rendered at 44.1 kHz on
// one core, REPEATS times. Prints the median wall time, the modes, the mode-samples per second and
// their share of the core's peak floating-point rate, and the stage table.
// Usage: clatter-synth-table-bench MODAL_BANK [REPEATS=5] [OBJECTS=328]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench/solid_ellipsoid.hpp"
#include "core/stage_log.hpp"
#include "synth/modal_source.hpp"
#include "synth/render_scene.hpp"
#include "tests/unit/make_material.hpp"

using namespace clatter;

namespace {

io::Scene table_setting(std::size_t n_objects, double duration_s) {
  std::mt19937_64 rng(20100725);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  io::Scene s;
  s.path = "generated table setting";
  s.materials["glass"] = clatter::test::damped(6.2e10, 0.2, 1.0, 1e-7);
  s.ground_material = "glass";
  const double pi = 3.14159265358979323846;
  for (std::size_t i = 0; i < n_objects; ++i) {
    // Solid glass pieces 3 cm across ring near 40 kHz: the near-spherical proxies of the demo
    // bank need 4-30 cm pieces to ring in 2-20 kHz, as the paper's thin shards do.
    const double a = 0.04 + 0.26 * u(rng), b = a * (0.6 + 0.4 * u(rng)), c = b * (0.6 + 0.4 * u(rng));
    io::SceneObject o = bench::solid_ellipsoid(static_cast<int>(i + 1), a, b, c, 2600, "glass");
    o.created_s = 0.2 * u(rng);  // the plates break in the first 0.2 s
    o.where = "object " + std::to_string(i);
    s.objects.push_back(o);
  }
  for (std::size_t i = 0; i < n_objects; ++i) {
    const io::SceneObject& o = s.objects[i];
    const int hits = 20;
    for (int k = 0; k <= hits; ++k) {
      io::SceneEvent e;
      e.t_s = k == 0 ? o.created_s : o.created_s + (duration_s - 0.5 - o.created_s) * std::pow(u(rng), 2.0);
      e.a = o.id;
      e.fracture = k == 0;
      e.contact_time_s = 2e-4;
      const double angle = 2 * pi * u(rng);
      e.pose_a.position_m = {u(rng) - 0.5, u(rng) - 0.5, 0.02 + 0.1 * u(rng)};
      e.pose_a.orientation_wxyz = {std::cos(angle / 2), std::sin(angle / 2) * 0.6, 0, std::sin(angle / 2) * 0.8};
      e.point_m = {e.pose_a.position_m[0], e.pose_a.position_m[1], e.pose_a.position_m[2] - 0.01};
      const double speed = 0.1 + 2.0 * u(rng), j = o.mass_kg * speed * 1.5;
      e.impulse_n_s = {0.3 * j * (u(rng) - 0.5), 0.3 * j * (u(rng) - 0.5), j};
      e.normal_speed_m_s = speed;
      e.where = "event " + std::to_string(s.events.size());
      s.events.push_back(e);
    }
  }
  std::stable_sort(s.events.begin(), s.events.end(), [](const io::SceneEvent& x, const io::SceneEvent& y) { return x.t_s < y.t_s; });
  s.listeners_m.push_back({0.0, 1.5, 0.8});
  s.duration_s = duration_s;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: clatter-synth-table-bench MODAL_BANK [REPEATS=5] [OBJECTS=328]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  const std::size_t objects = argc > 3 ? static_cast<std::size_t>(std::atol(argv[3])) : 328;
  const io::Scene scene = table_setting(objects, 5.0);
  synth::ModalSource modal(std::vector<std::string>{argv[1]});
  std::vector<double> walls;
  synth::RenderStats stats;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto out = synth::render_scene(scene, {&modal}, {}, &stats);
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::printf("run %d: %.3f s (%zu impacts, %zu samples)\n", r + 1, walls.back(), stats.impacts, out[0][0].size());
  }
  std::sort(walls.begin(), walls.end());
  const double median = walls[walls.size() / 2];
  const synth::ModalStats& m = modal.stats();
  const double mode_samples = static_cast<double>(m.resonators.mode_samples), stepped = static_cast<double>(m.resonators.stepped_samples);
  // Per stepped lane-sample: 2 multiplies and a subtraction (the recursion), 1 add (the lane sum).
  const double flops = 4 * stepped / median;
  std::printf("table setting: %zu objects, %zu modes rendered (%zu above 20 kHz, %zu below 20 Hz skipped), %zu impacts, 5 s at "
              "44.1 kHz, 1 core\n",
              m.objects, m.modes, m.skipped_high, m.skipped_low, stats.impacts);
  std::printf("  render: median %.3f s of %d (min %.3f, max %.3f); %.0fx faster than the paper's 20 min\n", median, repeats,
              walls.front(), walls.back(), 1200.0 / median);
  std::printf("  %zu excitations into %zu resonators; %.3g mode-samples (%.3g lane-samples stepped, %.0f %% useful): %.3g "
              "mode-samples/s\n",
              m.excitations, m.resonators.resonators, mode_samples, stepped, 100 * mode_samples / stepped, mode_samples / median);
  std::printf("  recursion: %.3g GFLOP/s (4 flops per lane-sample)\n", flops * 1e-9);
  std::printf("  stages, summed over the %d runs:\n", repeats);
  std::fputs(format_stage_table(merge_stage_entries({stage_log().entries()}), 1).c_str(), stdout);
  return 0;
}
