#pragma once
// When a long loop prints its progress line, and its ETA: due() at most once per interval_s (never
// with 0, the command line's --progress-interval), the ETA extrapolated from the share done at
// the pace so far. The solve's time loop and a PAN task's hearing through the Kirchhoff surface
// report through it; each line says what it counts.
#include <algorithm>
#include <chrono>

namespace clatter {

class ProgressTimer {
 public:
  explicit ProgressTimer(double interval_s) : interval_s_(interval_s), start_(Clock::now()), last_(start_) {}
  // True when a line is due; the next one is then an interval away.
  bool due() {
    if (interval_s_ <= 0) return false;
    const auto now = Clock::now();
    if (seconds(now - last_) < interval_s_) return false;
    last_ = now;
    return true;
  }
  double elapsed_s() const { return seconds(Clock::now() - start_); }
  // Seconds left with `done` (0-1) of the whole behind; only meaningful once done > 0.
  double eta_s(double done) const { return elapsed_s() * (1 - done) / std::max(done, 1e-9); }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }
  double interval_s_;
  Clock::time_point start_, last_;
};

}  // namespace clatter
