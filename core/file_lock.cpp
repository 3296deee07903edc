#include "core/file_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/cleanup.hpp"

namespace fs = std::filesystem;

namespace clatter {
namespace {

constexpr const char* kLockMagic = "clatter-lock 1";
constexpr double kGuardStaleS = 30;  // a breaker holds its guard for milliseconds
// Taking or judging a lock while others break it and take it in turn ends within this.
constexpr auto kContentionLimit = std::chrono::seconds(30);

std::optional<std::string> read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string first_line(const std::string& path) {
  const auto text = read_text(path);
  return text ? text->substr(0, text->find('\n')) : std::string();
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "unknown-host";
  return name;
}

// The start time of process `pid` in clock ticks since boot: field 22 of
// /proc/PID/stat, counted after the command name, which is in parentheses and
// may itself hold spaces.
std::optional<unsigned long long> proc_start_ticks(long pid) {
  const auto stat = read_text(fmt::format("/proc/{}/stat", pid));
  if (!stat) return std::nullopt;
  const auto close = stat->rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream in(stat->substr(close + 1));
  std::string field;
  for (int i = 3; i < 22 && in >> field;) ++i;
  unsigned long long ticks = 0;
  if (!(in >> ticks)) return std::nullopt;
  return ticks;
}

std::string env_text(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

LockOwner self_owner(const std::string& command) {
  LockOwner o;
  o.host = host_name();
  o.boot_id = first_line("/proc/sys/kernel/random/boot_id");
  o.pid = static_cast<long>(getpid());
  o.start_ticks = proc_start_ticks(o.pid).value_or(0);
  o.job = env_text("SLURM_JOB_ID");
  if (!o.job.empty() && !env_text("SLURM_ARRAY_TASK_ID").empty())
    o.job = fmt::format("{}_{}", o.job, env_text("SLURM_ARRAY_TASK_ID"));
  o.restart = std::atoi(env_text("SLURM_RESTART_COUNT").c_str());
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%dT%H:%M:%SZ", &utc);
  o.started_utc = stamp;
  o.command = command;
  for (char& c : o.command)
    if (c == '\n' || c == '\r') c = ' ';
  return o;
}

std::string serialize(const LockOwner& o) {
  return fmt::format(
      "{}\nhost={}\nboot_id={}\npid={}\nstart_ticks={}\njob={}\nrestart={}\nstarted_utc={}\ncommand={}\n", kLockMagic,
      o.host, o.boot_id, o.pid, o.start_ticks, o.job, o.restart, o.started_utc, o.command);
}

std::optional<LockOwner> parse(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kLockMagic) return std::nullopt;
  LockOwner o;
  try {
    while (std::getline(in, line)) {
      const auto eq = line.find('=');
      if (eq == std::string::npos) continue;
      const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
      if (key == "host") o.host = value;
      if (key == "boot_id") o.boot_id = value;
      if (key == "pid") o.pid = std::stol(value);
      if (key == "start_ticks") o.start_ticks = std::stoull(value);
      if (key == "job") o.job = value;
      if (key == "restart") o.restart = std::stoi(value);
      if (key == "started_utc") o.started_utc = value;
      if (key == "command") o.command = value;
    }
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (o.host.empty() || o.pid <= 0) return std::nullopt;
  return o;
}

double mtime_s(const struct stat& st) {
  return static_cast<double>(st.st_mtim.tv_sec) + 1e-9 * static_cast<double>(st.st_mtim.tv_nsec);
}

// Seconds since `path` was last touched, by the clock of the file server that
// holds it (a probe file's modification time), so clocks of different nodes do
// not enter. Null if `path` is gone.
std::optional<double> server_age_s(const std::string& path) {
  struct stat target {};
  if (::stat(path.c_str(), &target) != 0) return std::nullopt;
  const std::string probe = (fs::path(path).parent_path() /
                             fmt::format(".{}.probe-{}-{}", fs::path(path).filename().string(), host_name(), getpid()))
                                .string();
  double now_s = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  const int fd = ::open(probe.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0644);
  if (fd >= 0) {
    struct stat st {};
    if (::fstat(fd, &st) == 0) now_s = mtime_s(st);
    ::close(fd);
    ::unlink(probe.c_str());
  }
  return now_s - mtime_s(target);
}

struct Verdict {
  enum { gone, live, stale } state = gone;
  std::string why;  // stale: why; live: how it was told (heartbeat age)
  LockOwner owner;
};

Verdict judge(const std::string& path, const std::string& text, const LockTiming& timing) {
  const auto age = server_age_s(path);
  if (!age) return {};
  const auto owner = parse(text);
  if (!owner) {  // not written by this code: only its age can tell
    if (*age > timing.stale_after_s)
      return {Verdict::stale, fmt::format("unreadable, untouched for {:.0f} s", *age), {}};
    return {Verdict::live, "an unreadable lock file", LockOwner{"?", "", 0, 0, "", 0, "?", ""}};
  }
  const LockOwner me = self_owner("");
  if (!owner->job.empty() && owner->job == me.job && owner->restart < me.restart)
    return {Verdict::stale, fmt::format("Slurm job {} was requeued since (restart {})", me.job, me.restart), *owner};
  if (owner->host == me.host) {
    if (owner->boot_id != me.boot_id) return {Verdict::stale, "the host rebooted since", *owner};
    const auto ticks = proc_start_ticks(owner->pid);
    if (!ticks) return {Verdict::stale, fmt::format("process {} is gone", owner->pid), *owner};
    if (*ticks != owner->start_ticks)
      return {Verdict::stale, fmt::format("PID {} now belongs to another process", owner->pid), *owner};
    return {Verdict::live, "", *owner};
  }
  if (*age > timing.stale_after_s)
    return {Verdict::stale, fmt::format("no heartbeat for {:.0f} s (stale after {:.0f} s)", *age, timing.stale_after_s),
            *owner};
  return {Verdict::live, fmt::format("last heartbeat {:.0f} s ago", std::max(*age, 0.0)), *owner};
}

// link(2) onto an existing name fails on every file system; over NFS a lost
// reply can report a failure that happened, so success is read off the
// temporary's link count.
bool try_link(const std::string& temp, const std::string& path) {
  if (::link(temp.c_str(), path.c_str()) == 0) return true;
  const int error = errno;
  struct stat st {};
  if (::stat(temp.c_str(), &st) == 0 && st.st_nlink == 2) return true;
  if (error != EEXIST)
    throw std::runtime_error(fmt::format("{}: cannot take the lock: link(2): {}", path, std::strerror(error)));
  return false;
}

// Removes the stale lock `path` if it still says `seen`. Breakers take a guard
// file first, so that two of them cannot both remove: the second would remove a
// fresh lock the first just took.
void break_stale(const std::string& path, const std::string& seen) {
  const std::string guard = path + ".break";
  const int fd = ::open(guard.c_str(), O_CREAT | O_EXCL | O_WRONLY, 0644);
  if (fd < 0) {
    if (const auto age = server_age_s(guard); age && *age > kGuardStaleS) ::unlink(guard.c_str());
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    return;
  }
  ::close(fd);
  if (read_text(path) == seen) ::unlink(path.c_str());
  ::unlink(guard.c_str());
}

unsigned long long inode_of(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 ? static_cast<unsigned long long>(st.st_ino) : 0;
}

}  // namespace

std::string LockOwner::describe() const {
  return fmt::format("host {}, PID {}, since {}", host, pid, started_utc.empty() ? "?" : started_utc);
}

LockHeld::LockHeld(const std::string& path, const LockOwner& owner, const std::string& detail)
    : InputError(fmt::format("{}: locked by {}{}{}: another run is writing this output; wait for it or stop it", path,
                             owner.describe(), detail.empty() ? "" : ", ", detail)) {}

std::optional<LockOwner> FileLock::live_owner(const std::string& path, const LockTiming& timing,
                                              const LockNotice& notice) {
  for (const auto until = std::chrono::steady_clock::now() + kContentionLimit; std::chrono::steady_clock::now() < until;) {
    const auto text = read_text(path);
    if (!text) return std::nullopt;
    const Verdict v = judge(path, *text, timing);
    if (v.state == Verdict::gone) return std::nullopt;
    if (v.state == Verdict::live) return v.owner;
    if (notice) notice(fmt::format("{}: breaking the stale lock of {}: {}", path, v.owner.describe(), v.why));
    break_stale(path, *text);
  }
  throw std::runtime_error(path + ": the lock kept changing hands for 30 s while being checked");
}

FileLock::FileLock(const std::string& path, const std::string& command, const LockTiming& timing,
                   const LockNotice& notice)
    : path_(path), text_(serialize(self_owner(command))), timing_(timing) {
  const fs::path p(path);
  const std::string temp =
      (p.parent_path() / fmt::format(".{}.tmp-{}-{}", p.filename().string(), host_name(), getpid())).string();
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out << text_;
    out.flush();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the lock's temporary {}", path, temp));
  }
  const struct RemoveTemp {
    const std::string& path;
    ~RemoveTemp() { ::unlink(path.c_str()); }
  } remove_temp{temp};
  bool taken = false;
  for (const auto until = std::chrono::steady_clock::now() + kContentionLimit;
       !taken && std::chrono::steady_clock::now() < until;) {
    taken = try_link(temp, path);
    if (taken) break;
    const auto text = read_text(path);
    if (!text) continue;  // released in between
    const Verdict v = judge(path, *text, timing);
    if (v.state == Verdict::live) throw LockHeld(path, v.owner, v.why);
    if (v.state == Verdict::stale) {
      if (notice) notice(fmt::format("{}: breaking the stale lock of {}: {}", path, v.owner.describe(), v.why));
      break_stale(path, *text);
    }
  }
  if (!taken) throw std::runtime_error(path + ": cannot take the lock: it kept changing hands for 30 s");
  inode_ = inode_of(path);
  register_temporary(path);  // removed on an abort path that skips destructors
  beat_ = std::thread([this] { heartbeat(); });
}

void FileLock::heartbeat() {
  const auto period = std::chrono::duration<double>(timing_.heartbeat_s);
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, period, [this] { return stop_; }))
    if (inode_of(path_) != inode_ || ::utimensat(AT_FDCWD, path_.c_str(), nullptr, 0) != 0) lost_ = true;
}

bool FileLock::still_held() const { return !lost_ && inode_of(path_) == inode_ && read_text(path_) == text_; }

FileLock::~FileLock() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (beat_.joinable()) beat_.join();
  unregister_temporary(path_);
  if (still_held()) ::unlink(path_.c_str());
}

}  // namespace clatter
