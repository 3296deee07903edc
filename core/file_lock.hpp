#pragma once
// An exclusive lock on an output, for one writer per output across the nodes of
// a cluster (docs/cluster.md, "One writer per output"). The lock is a small
// text file naming its owner. It is taken by link(2) of a complete temporary
// onto the lock's name, which is atomic and fails when the name exists on every
// POSIX file system, NFS, Lustre and GPFS included (flock/fcntl locks are not:
// Lustre and GPFS mounts often lack them across nodes). While held, a thread
// touches the file every heartbeat. A lock whose owner is gone is stale and is
// broken:
//   same host: the recorded PID is no longer the recorded process (start time),
//   or the host rebooted; same Slurm job, later restart: a requeued job's
//   earlier run is dead; another host: no heartbeat for stale_after_s, measured
//   by the file server's clock.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/errors.hpp"

namespace clatter {

// Who holds a lock, as its file records it.
struct LockOwner {
  std::string host, boot_id;
  long pid = 0;
  unsigned long long start_ticks = 0;  // the process's start (/proc/PID/stat), so a reused PID is told apart
  std::string job;                     // SLURM_JOB_ID (and _ARRAY_TASK_ID), or empty
  int restart = 0;                     // SLURM_RESTART_COUNT
  std::string started_utc;
  std::string command;
  std::string describe() const;  // "host H, PID P, since T"
};

struct LockTiming {
  double heartbeat_s = 10;    // the holder touches its lock this often
  double stale_after_s = 60;  // a lock of another host without a heartbeat for this long is stale
};

// Another run holds the lock: bad input in the sense of core/errors.hpp (exit
// 2), nothing changed.
class LockHeld : public InputError {
 public:
  LockHeld(const std::string& path, const LockOwner& owner, const std::string& detail);
};

// Notices for the log: a stale lock broken, and why.
using LockNotice = std::function<void(const std::string&)>;

class FileLock {
 public:
  // Takes the lock file `path` (its folder must exist) or throws LockHeld.
  FileLock(const std::string& path, const std::string& command, const LockTiming& timing, const LockNotice& notice);
  ~FileLock();  // releases it, if it is still this process's
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

  const std::string& path() const { return path_; }
  // False once another process broke the lock (it judged this one stale) or the
  // file is gone.
  bool still_held() const;

  // The live owner of the lock file `path`, if any; a stale one is broken (and
  // reported).
  static std::optional<LockOwner> live_owner(const std::string& path, const LockTiming& timing,
                                             const LockNotice& notice);

 private:
  void heartbeat();
  std::string path_, text_;
  unsigned long long inode_ = 0;
  LockTiming timing_;
  std::atomic<bool> lost_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread beat_;
};

}  // namespace clatter
