#pragma once
// From the simulator's per-step contact points to scene events (docs/synth.md, "From a
// rigid-body simulator"). Bullet reports each manifold point's impulse once per step; a sound
// source wants one impact per collision. The rule:
//  1. Contact points of one pair of bodies (or a body and the ground) within `merge_distance_m`
//     of each other belong to one *episode*: a face or an edge landing is one impact, and a point
//     that Bullet drops and re-creates a step later (its convex-convex clipping makes new points
//     every step) continues it. An episode begins at the first step with an impulse there and ends
//     once none has come for longer than `quiet_s` (shorter gaps are the solver's flicker on a
//     resting contact).
//  2. An episode's impulse is the sum of its steps' impulses (so momentum is kept exactly), its
//     point the impulse-weighted mean position, its time when the surfaces met in its first step
//     (sim/world.hpp, touch_after_s), its poses and its normal speed those of the first step (the
//     fastest of its points).
//  3. The first episode of a point is an *impact* (Hertz duration from its normal speed) and lasts
//     at most `impact_window_s`: a rigid-body solver delivers a collision's impulse within a few
//     steps. A point still pushing then continues as *sustained contact* episodes (resting,
//     sliding, rolling) of at most `sustain_window_s` each, whose force is spread over the
//     episode's own length (event key contact_time_s): a resting body makes no click.
//  4. A first episode whose point did not approach (normal speed <= min_speed_m_s) is sustained
//     too: a body set down on another, or pressed by a neighbour, makes no impact.
#include <cstdint>
#include <map>
#include <vector>

#include "io/scene.hpp"
#include "sim/world.hpp"

namespace clatter::sim {

class ImpactRecorder {
 public:
  struct Rules {
    double impact_window_s = 2e-3, sustain_window_s = 0.1, quiet_s = 1e-3, min_speed_m_s = 0.05, merge_distance_m = 0.01;
  };
  ImpactRecorder(double dt_s, const Rules& rules);
  // The contacts of the step that started at t_s.
  void add_step(double t_s, const std::vector<ContactSample>& contacts);
  // Adds an event made elsewhere (a fracture impulse) in its place in time.
  void add_event(const io::SceneEvent& e);
  // Closes the open episodes and returns every event in time order (ties: the order they began).
  std::vector<io::SceneEvent> finish();

  std::size_t impacts() const { return impacts_; }
  std::size_t sustained() const { return sustained_; }

 private:
  struct Episode {
    io::SceneEvent event;
    Vec3 weighted_point{}, last_point{};
    double weight = 0;
    long long first_step = 0, last_step = 0;
    bool continuation = false;
    std::uint64_t serial = 0;
  };
  void close(Episode& e);
  double dt_s_;
  Rules rules_;
  std::map<std::pair<int, int>, std::vector<Episode>> open_;  // by the pair (a, b)
  std::vector<std::pair<std::uint64_t, io::SceneEvent>> done_;  // (serial, event)
  std::uint64_t serial_ = 0;
  std::size_t impacts_ = 0, sustained_ = 0;
};

}  // namespace clatter::sim
