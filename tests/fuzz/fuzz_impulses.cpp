// The James-lab impulse reader (io::read_impulse_events) against a fixed side scene, the demo's
// objects and materials (CLATTER_FUZZ_SIDE_SCENE, read once). Only InputError may come out.
#include "core/errors.hpp"
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {
const clatter::io::Scene& side_scene() {
  static const clatter::io::Scene scene = clatter::io::read_scene(CLATTER_FUZZ_SIDE_SCENE, false);
  return scene;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = clatter::fuzz::write_input(data, size, "impulses.txt");
  clatter::io::Scene scene = side_scene();
  try {
    clatter::io::read_impulse_events(path, scene);
    for (std::size_t i = 1; i < scene.events.size(); ++i)
      if (scene.events[i].t_s < scene.events[i - 1].t_s) clatter::fuzz::broken("events out of time order");
  } catch (const clatter::InputError&) {
  }
  return 0;
}
