// clatter-test-mesh: writes the test meshes of tests/unit/test_meshes.hpp as OBJ files, for runs of
// the programs on shapes with independent references (tests/reference/bar_modes.hpp,
// circular_plate.hpp; docs/validation.md):
//   clatter-test-mesh bar LENGTH_M WIDTH_M DEPTH_M NX NY NZ OUT.obj
//   clatter-test-mesh disk RADIUS_M THICKNESS_M SEGMENTS RINGS OUT.obj
//   clatter-test-mesh box A_M B_M C_M N OUT.obj
//   clatter-test-mesh sphere RADIUS_M LEVELS OUT.obj
// Exit 0 done, 1 the file cannot be written, 2 bad arguments.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/unit/test_meshes.hpp"

namespace {

int usage() {
  std::fputs("usage: clatter-test-mesh bar L B H NX NY NZ OUT.obj | disk R T SEGMENTS RINGS OUT.obj | box A B C N OUT.obj | "
             "sphere R LEVELS OUT.obj\n",
             stderr);
  return 2;
}

bool number(const std::string& s, double& x) {
  char* end = nullptr;
  x = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == 0 && x > 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> a(argv + 1, argv + argc);
  if (a.empty()) return usage();
  const std::size_t want = a[0] == "bar" ? 8 : a[0] == "disk" ? 6 : a[0] == "box" ? 6 : a[0] == "sphere" ? 4 : 0;
  if (!want || a.size() != want) return usage();
  std::vector<double> x(want - 2);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!number(a[i + 1], x[i])) return usage();
  auto count = [](double v) { return static_cast<int>(v); };
  clatter::io::TriangleMesh m;
  if (a[0] == "bar") m = clatter::test::bar({x[0], x[1], x[2]}, {count(x[3]), count(x[4]), count(x[5])});
  if (a[0] == "disk") m = clatter::test::disk(x[0], x[1], count(x[2]), count(x[3]));
  if (a[0] == "box") m = clatter::test::box({x[0], x[1], x[2]}, count(x[3]));
  if (a[0] == "sphere") m = clatter::test::icosphere(x[0], count(x[1]));
  // The tests write into a build folder that no other test may have made yet (a clean clone).
  const std::filesystem::path out(a.back());
  std::error_code ec;
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path(), ec);
  if (ec || !clatter::test::write_obj(m, a.back())) {
    std::fprintf(stderr, "clatter-test-mesh: cannot write %s\n", a.back().c_str());
    return 1;
  }
  std::printf("clatter-test-mesh: wrote %s: %zu vertices, %zu triangles\n", a.back().c_str(), m.vertices_m.size(), m.triangles.size());
  return 0;
}
