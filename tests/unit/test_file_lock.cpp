// core/file_lock: one holder at a time, released on destruction, and each kind of stale lock
// (docs/cluster.md, "One writer per output") told apart from a live one.
#include "core/file_lock.hpp"

#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;
using clatter::FileLock;
using clatter::LockHeld;
using clatter::LockTiming;

namespace {

class FileLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("clatter-lock-test-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name = "out.h5.lock") const { return (dir_ / name).string(); }
  // A lock file as another process would leave it.
  void write_lock(const std::string& host, long pid, unsigned long long ticks, const std::string& boot_id) const {
    std::ofstream(path()) << "clatter-lock 1\nhost=" << host << "\nboot_id=" << boot_id << "\npid=" << pid
                          << "\nstart_ticks=" << ticks << "\njob=\nrestart=0\nstarted_utc=2026-01-01T00:00:00Z\n"
                          << "command=test\n";
  }
  static std::string read(const std::string& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static std::string field(const std::string& text, const std::string& key) {
    const auto at = text.find("\n" + key + "=");
    return text.substr(at + key.size() + 2, text.find('\n', at + 1) - at - key.size() - 2);
  }
  fs::path dir_;
  LockTiming timing_{0.05, 1.0};
  std::vector<std::string> notices_;
  clatter::LockNotice notice_ = [this](const std::string& s) { notices_.push_back(s); };
};

TEST_F(FileLockTest, OneHolderAtATimeAndReleasedOnDestruction) {
  {
    FileLock lock(path(), "first", timing_, notice_);
    EXPECT_TRUE(lock.still_held());
    const std::string text = read(path());
    EXPECT_EQ(field(text, "pid"), std::to_string(getpid()));
    EXPECT_EQ(field(text, "command"), "first");
    try {
      FileLock second(path(), "second", timing_, notice_);
      FAIL() << "a second lock was taken while the first is held";
    } catch (const LockHeld& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("locked by host"), std::string::npos) << what;
      EXPECT_NE(what.find("PID " + std::to_string(getpid())), std::string::npos) << what;
    }
    EXPECT_TRUE(lock.still_held());  // the refused attempt left the holder's lock alone
  }
  EXPECT_FALSE(fs::exists(path()));
  for (const auto& e : fs::directory_iterator(dir_)) ADD_FAILURE() << "left behind: " << e.path();
  FileLock again(path(), "third", timing_, notice_);
  EXPECT_TRUE(notices_.empty());
}

TEST_F(FileLockTest, HeartbeatAdvancesTheModificationTime) {
  FileLock lock(path(), "beat", timing_, notice_);
  const auto before = fs::last_write_time(path());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_GT(fs::last_write_time(path()), before);
}

TEST_F(FileLockTest, ALockOfAProcessThatDiedIsBroken) {
  const pid_t child = fork();
  if (child == 0) {  // takes the lock and dies without releasing it, like SIGKILL
    FileLock* lock = new FileLock(path(), "child", timing_, nullptr);
    (void)lock;
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(fs::exists(path()));
  FileLock lock(path(), "after", timing_, notice_);
  ASSERT_EQ(notices_.size(), 1u);
  EXPECT_NE(notices_[0].find("process " + std::to_string(child) + " is gone"), std::string::npos) << notices_[0];
  EXPECT_TRUE(lock.still_held());
}

TEST_F(FileLockTest, AReusedPidOrARebootIsStale) {
  std::string boot_id;
  std::ifstream("/proc/sys/kernel/random/boot_id") >> boot_id;
  char host[256] = {};
  gethostname(host, sizeof(host) - 1);
  write_lock(host, getpid(), 1, boot_id);  // this PID, but a process that started at tick 1
  { FileLock lock(path(), "reused", timing_, notice_); }
  ASSERT_EQ(notices_.size(), 1u);
  EXPECT_NE(notices_[0].find("now belongs to another process"), std::string::npos) << notices_[0];
  write_lock(host, getpid(), 1, "another-boot");
  { FileLock lock(path(), "rebooted", timing_, notice_); }
  ASSERT_EQ(notices_.size(), 2u);
  EXPECT_NE(notices_[1].find("the host rebooted since"), std::string::npos) << notices_[1];
}

TEST_F(FileLockTest, AnotherHostsLockIsStaleOnlyWithoutAHeartbeat) {
  write_lock("other-node", 4242, 1, "x");
  EXPECT_THROW(FileLock(path(), "fresh", timing_, notice_), LockHeld);
  EXPECT_TRUE(notices_.empty());
  fs::last_write_time(path(), fs::file_time_type::clock::now() - std::chrono::seconds(5));
  FileLock lock(path(), "stale", timing_, notice_);  // stale_after_s = 1
  ASSERT_EQ(notices_.size(), 1u);
  EXPECT_NE(notices_[0].find("host other-node, PID 4242"), std::string::npos) << notices_[0];
  EXPECT_NE(notices_[0].find("no heartbeat for"), std::string::npos) << notices_[0];
}

TEST_F(FileLockTest, AnUnreadableLockIsJudgedByItsAgeAlone) {
  std::ofstream(path()) << "not a lock\n";
  EXPECT_THROW(FileLock(path(), "fresh", timing_, notice_), LockHeld);
  fs::last_write_time(path(), fs::file_time_type::clock::now() - std::chrono::seconds(5));
  FileLock lock(path(), "old", timing_, notice_);
  EXPECT_EQ(notices_.size(), 1u);
}

TEST_F(FileLockTest, AHolderNoticesWhenItsLockWasTaken) {
  FileLock lock(path(), "holder", timing_, notice_);
  fs::remove(path());
  write_lock("other-node", 4242, 1, "x");  // another run judged it stale and took it
  EXPECT_FALSE(lock.still_held());
  // Releasing leaves the other run's lock in place.
}

TEST_F(FileLockTest, LiveOwnerOfAFreeOrStaleLockIsNone) {
  EXPECT_FALSE(FileLock::live_owner(path(), timing_, notice_));
  write_lock("other-node", 4242, 1, "x");
  const auto owner = FileLock::live_owner(path(), timing_, notice_);
  ASSERT_TRUE(owner);
  EXPECT_EQ(owner->host, "other-node");
  EXPECT_EQ(owner->pid, 4242);
  fs::last_write_time(path(), fs::file_time_type::clock::now() - std::chrono::seconds(5));
  EXPECT_FALSE(FileLock::live_owner(path(), timing_, notice_));
  EXPECT_FALSE(fs::exists(path()));
}

// Processes race to take one lock. Every holder leaves it stale (as if killed), so each hand-over
// is a race of breakers: at most one is ever inside (each marks its stay with an exclusive-create
// file), and every one gets in eventually.
TEST_F(FileLockTest, RacingProcessesNeverHoldItTogether) {
  const pid_t dead = fork();
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  char host[256] = {};
  gethostname(host, sizeof(host) - 1);
  std::string boot_id;
  std::ifstream("/proc/sys/kernel/random/boot_id") >> boot_id;
  write_lock(host, dead, 1, boot_id);
  const std::string stale = read(path());
  const std::string inside = path("inside"), overlap = path("overlap");
  std::vector<pid_t> children;
  for (int c = 0; c < 6; ++c) {
    const pid_t child = fork();
    if (child == 0) {
      int entered = 0;
      for (int attempt = 0; attempt < 2000 && entered < 5; ++attempt) {
        try {
          FileLock lock(path(), "racer", timing_, nullptr);
          const int fd = ::open(inside.c_str(), O_CREAT | O_EXCL | O_WRONLY, 0644);
          if (fd < 0) std::ofstream(overlap) << "two holders\n";
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
          if (fd >= 0) {
            ::close(fd);
            ::unlink(inside.c_str());
          }
          const std::string temp = path("stale-" + std::to_string(getpid()));
          std::ofstream(temp) << stale;
          fs::rename(temp, path());  // dies holding it: the lock now names a dead process
          ++entered;
        } catch (const LockHeld&) {
          std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
      }
      _exit(entered == 5 ? 0 : 1);
    }
    children.push_back(child);
  }
  for (pid_t child : children) {
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a racer never got the lock";
  }
  EXPECT_FALSE(fs::exists(overlap)) << "two processes held the lock at once";
}

}  // namespace
