#pragma once
// clatter-sim's job: a config (sim/simulate.cpp's schema; scenes/*.toml) -> the bodies (meshes, a
// Voronoi pre-fractured plate, a pile of Voronoi rocks) -> Bullet, stepped at a fixed rate -> the
// contact and fracture impulses as a native scene (docs/scene-format.md).
#include <functional>
#include <map>
#include <string>

#include "io/config.hpp"
#include "io/scene.hpp"
#include "sim/fracture.hpp"
#include "sim/world.hpp"

namespace clatter::sim {

const io::Schema& sim_schema();

struct SimStats {
  std::size_t steps = 0, contact_samples = 0;
  std::size_t impacts = 0, sustained = 0, fracture_events = 0;
  double fracture_s = -1;  // when the plate (or the first breakable body) broke (-1: never)
  FractureStats fracture;  // the breakable bodies' stress solves and fractures
  double wall_s = 0;
  std::map<int, BodyState> final_states;  // every body alive at the end, by scene id
};

// Progress: called about every 10 % of the steps (and every 10 s) with (steps done, steps in all).
using Progress = std::function<void(std::size_t, std::size_t)>;
// Called at each fracture as it happens, with its record (the scene's fractures[]).
using FractureReport = std::function<void(const io::SceneFracture&)>;

// Runs the simulation the config describes; InputError names the config key (or mesh file) at fault.
// `config_path` resolves relative mesh paths.
io::Scene simulate(const io::Config& config, const std::string& config_path, SimStats* stats = nullptr,
                   const Progress& progress = {}, const FractureReport& on_fracture = {});

}  // namespace clatter::sim
