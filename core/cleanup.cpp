#include "core/cleanup.hpp"

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <vector>

namespace clatter {
namespace {
std::mutex g_mutex;
std::vector<std::string>& registry() {
  static std::vector<std::string> paths;
  return paths;
}
}  // namespace

void register_temporary(const std::string& path) {
  std::lock_guard lock(g_mutex);
  registry().push_back(path);
}

void unregister_temporary(const std::string& path) {
  std::lock_guard lock(g_mutex);
  auto& paths = registry();
  paths.erase(std::remove(paths.begin(), paths.end(), path), paths.end());
}

int remove_registered_temporaries() noexcept {
  std::lock_guard lock(g_mutex);
  int removed = 0;
  for (const auto& p : registry()) removed += std::remove(p.c_str()) == 0 ? 1 : 0;
  registry().clear();
  return removed;
}

}  // namespace clatter
