#include "sweep/output_guard.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/errors.hpp"
#include "io/h5.hpp"
#include "io/sweep_files.hpp"
#include "mpi/comm.hpp"

namespace fs = std::filesystem;

namespace clatter::jobs {
namespace {

double env_seconds(const char* name, double fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const double s = std::strtod(text, &end);
  if (*end != '\0' || !std::isfinite(s) || s <= 0)
    throw InputError(fmt::format("environment variable {}='{}': expected a number of seconds > 0", name, text));
  return s;
}

// The slice count of results folder lock `name` (base: "R.lock"): 1 for the
// whole sweep's, N for "R.lock-slice-K-of-N", 0 for anything else.
int slice_count_of(const std::string& name, const std::string& base) {
  if (name == base) return 1;
  const std::string prefix = base + "-slice-";
  if (name.rfind(prefix, 0) != 0) return 0;
  const auto of = name.find("-of-", prefix.size());
  return of == std::string::npos ? 0 : std::atoi(name.c_str() + of + 4);
}

fs::path folder_of(const fs::path& p) { return p.parent_path().empty() ? fs::path(".") : p.parent_path(); }

// `name` in the folder of `p`, spelled as the user spelled `p` (no "./" before a bare name).
std::string beside(const fs::path& p, const std::string& name) { return (p.parent_path() / name).string(); }

void log_notice(const std::string& text) { spdlog::warn("lock: {}", text); }

}  // namespace

LockTiming lock_timing() {
  LockTiming t;
  t.heartbeat_s = env_seconds("CLATTER_LOCK_HEARTBEAT_S", t.heartbeat_s);
  t.stale_after_s = env_seconds("CLATTER_LOCK_STALE_S", t.stale_after_s);
  return t;
}

SweepLocks::SweepLocks(MPI_Comm world, const std::string& results_dir, int slice_index, int slice_count,
                       const std::string& out, const std::string& command) {
  mpi::agree(world, [&] {
    if (mpi::rank(world) != 0) return;
    const LockTiming timing = lock_timing();
    std::vector<std::unique_ptr<FileLock>> taken;  // released again if a later one is refused
    fs::path results = fs::path(results_dir).lexically_normal();
    if (results.filename().empty()) results = results.parent_path();
    const fs::path folder = folder_of(results);
    fs::create_directories(folder);
    const std::string base = results.filename().string() + ".lock";
    const std::string own = slice_count == 1 ? base : fmt::format("{}-slice-{}-of-{}", base, slice_index, slice_count);
    taken.push_back(std::make_unique<FileLock>(beside(results, own), command, timing, log_notice));
    for (const auto& entry : fs::directory_iterator(folder)) {
      const std::string name = entry.path().filename().string();
      const int n = slice_count_of(name, base);
      if (name == own || n == 0 || n == slice_count) continue;
      const std::string path = beside(results, name);
      if (auto owner = FileLock::live_owner(path, timing, log_notice))
        throw LockHeld(path, *owner,
                       fmt::format("which runs {} of {}", n == 1 ? "the whole sweep or a merge" : "slices", results_dir));
    }
    if (!out.empty()) {
      fs::create_directories(folder_of(out));
      taken.push_back(std::make_unique<FileLock>(out + ".lock", command, timing, log_notice));
    }
    locks_ = std::move(taken);
  });
}

void SweepLocks::check_held() const {
  for (const auto& lock : locks_)
    if (!lock->still_held())
      throw std::runtime_error(fmt::format(
          "{}: this run's lock was broken by another run (it judged this one stale); nothing written", lock->path()));
}

void check_replace(const std::string& out, const model::SweepStatus& merged, bool force) {
  if (!fs::exists(out)) return;
  std::string holds;
  try {
    const auto file = io::File::open(out);
    const model::SweepStatus old = io::read_sweep_status(file);
    if (!old.sweep_id.empty() && old.sweep_id == merged.sweep_id) {
      if (merged.tasks_done() >= old.tasks_done()) return;
      holds = fmt::format("{} of {} tasks of this sweep, more than the {} of this merge", old.tasks_done(),
                          old.tasks_total, merged.tasks_done());
    } else {
      holds = fmt::format("a {} bank of another sweep (sweep id {}; this one's is {})",
                          old.complete() ? "complete" : "partial", old.sweep_id.empty() ? "not recorded" : old.sweep_id,
                          merged.sweep_id);
    }
  } catch (const std::exception& e) {
    holds = fmt::format("no bank of a sweep ({})", e.what());
  }
  if (force) {
    spdlog::warn("merge: replacing {}, which holds {} (--force)", out, holds);
    return;
  }
  throw InputError(
      fmt::format("{}: holds {}; not replaced (--force replaces it; or choose another --out)", out, holds));
}

bool holds_complete_bank(const std::string& out, const std::string& sweep_id) {
  if (!fs::exists(out)) return false;
  try {
    const model::SweepStatus old = io::read_sweep_status(io::File::open(out));
    return old.sweep_id == sweep_id && old.complete();
  } catch (const std::exception&) {
    return false;  // not a bank: check_replace says what it holds
  }
}

}  // namespace clatter::jobs
