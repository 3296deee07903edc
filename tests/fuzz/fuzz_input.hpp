#pragma once
// What every harness shares: the readers take paths, so each input is written to a file in
// /dev/shm (memory, no disk latency), one name per process so parallel fuzzing jobs do not collide.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace clatter::fuzz {

inline std::string scratch_path(const std::string& suffix) {
  return "/dev/shm/clatter-fuzz-" + std::to_string(::getpid()) + "-" + suffix;
}

// Writes the input to scratch_path(suffix); returns that path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& suffix) {
  const std::string path = scratch_path(suffix);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
    std::perror(path.c_str());
    std::abort();  // a harness that cannot write its input would test nothing
  }
  return path;
}

// A reader broke a promise it makes to its callers: reported by libFuzzer as a crash.
[[noreturn]] inline void broken(const char* what) {
  std::fprintf(stderr, "fuzz: reader postcondition violated: %s\n", what);
  std::abort();
}

}  // namespace clatter::fuzz
