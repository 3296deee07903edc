// The Wavefront OBJ reader (io::read_obj): only InputError may come out, and a mesh it returns has
// every index in range and no repeated corner (what the mass properties rely on).
#include "core/errors.hpp"
#include "io/mesh.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = clatter::fuzz::write_input(data, size, "mesh.obj");
  try {
    const clatter::io::TriangleMesh mesh = clatter::io::read_obj(path);
    const int n = static_cast<int>(mesh.vertices_m.size());
    for (const auto& t : mesh.triangles) {
      for (int v : t)
        if (v < 0 || v >= n) clatter::fuzz::broken("triangle index out of range");
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) clatter::fuzz::broken("repeated corner");
    }
  } catch (const clatter::InputError&) {
  }
  return 0;
}
