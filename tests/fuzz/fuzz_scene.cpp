// The JSON scene reader (io::read_scene, docs/scene-format.md). Bad input must end in InputError;
// any other exception escapes and libFuzzer reports it.
#include "core/errors.hpp"
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = clatter::fuzz::write_input(data, size, "scene.json");
  try {
    const clatter::io::Scene scene = clatter::io::read_scene(path);
    for (const auto& e : scene.events)
      if (e.a < 1 || e.b < 0) clatter::fuzz::broken("event with an invalid object id");
  } catch (const clatter::InputError&) {
  }
  return 0;
}
