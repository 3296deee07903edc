#pragma once
// Banks are never lost (docs/cluster.md, "One writer per output"):
//   SweepLocks     one writer per results folder and output, for a whole sweep,
//   a slice of one,
//                  or a merge, from before either is touched until the run
//                  ends;
//   check_replace  a merge never replaces a bank holding more of the same
//   sweep, nor a bank of
//                  another sweep (or no bank at all), unless --force.
// Every bank kind built by the sweep engine (sweep/sweep.hpp) goes through both.
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "core/file_lock.hpp"
#include "model/sweep_status.hpp"

namespace clatter::jobs {

class SweepLocks {
 public:
  // Collective over `world`; rank 0 takes the locks. Results folder R is locked
  // by R.lock (whole sweeps and merges, slice count 1) or R.lock-slice-K-of-N
  // (slice K of N): slices of one N run side by side, anything else on R is
  // refused. `out`, when not empty, is locked by OUT.lock. LockHeld (exit 2) on
  // every rank when another run holds one; nothing is left behind then.
  SweepLocks(MPI_Comm world, const std::string& results_dir, int slice_index, int slice_count, const std::string& out,
             const std::string& command);
  // Rank 0: throws std::runtime_error unless every lock is still this run's
  // (nobody broke it).
  void check_held() const;

 private:
  std::vector<std::unique_ptr<FileLock>> locks_;  // rank 0 only; released in reverse order
};

// The heartbeat and staleness of locks: CLATTER_LOCK_HEARTBEAT_S and
// CLATTER_LOCK_STALE_S from the environment (seconds), else 10 and 60.
LockTiming lock_timing();

// On rank 0, before a merge writes `out`: returns when `merged` may replace
// what is there, else throws InputError saying what `out` holds and why it
// stays. `force` replaces anything.
void check_replace(const std::string& out, const model::SweepStatus& merged, bool force);

// Whether `out` is a complete bank of the sweep `sweep_id` (false when it is missing, partial, of
// another sweep or unreadable): a resumed run has nothing left to do there.
bool holds_complete_bank(const std::string& out, const std::string& sweep_id);

}  // namespace clatter::jobs
