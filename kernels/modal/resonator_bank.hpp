#pragma once
// Every excited mode of a scene as a damped two-pole resonator, mixed into one output buffer.
// A mode's response to a half-sine contact (half_sine_response.hpp) is evaluated exactly at the
// samples during contact; afterwards it is the damped sinusoid y_n = Im(C e^{s t_n}), for which
//   y_n = a1 y_{n-1} - a2 y_{n-2},  a1 = 2 e^{Re(s) dt} cos(Im(s) dt),  a2 = e^{2 Re(s) dt}
// holds exactly. Later excitations of the same mode are injected into the same resonator (the
// system is linear), so a mode costs one recursion however often it is struck. Resonators run
// eight in lockstep so the compiler can vectorize across them, from their first injection until
// an upper bound of their envelope falls below `relative_floor` times the loudest resonator's
// (0: to the end), where each is cut to zero.
#include <complex>
#include <cstdint>
#include <limits>
#include <vector>

#include "kernels/modal/half_sine_response.hpp"

namespace clatter::kernels::modal {

struct ResonatorCounts {
  std::size_t resonators = 0, injections = 0;
  std::uint64_t mode_samples = 0;      // samples that resonators were alive for (the useful work)
  std::uint64_t stepped_samples = 0;   // lane-samples stepped, idle lanes of a lockstep group included
};

class ResonatorBank {
 public:
  explicit ResonatorBank(double rate_hz) : rate_hz_(rate_hz) {}

  // A resonator for the pole s [1/s] (Re s < 0 decays); its index.
  std::size_t add(std::complex<double> pole_1_s);

  // Adds weight * q(t - t0) to `out` (sample n at t = n / rate): the contact samples directly,
  // the rest through resonator r's recursion at render().
  void excite(std::size_t r, double t0_s, const HalfSineResponse& response, double weight, std::vector<double>& out);

  // From sample `first` on, resonator r also carries Im(phasor e^{s (t_n - t0)}).
  void inject(std::size_t r, std::int64_t first, std::complex<double> phasor, double t0_s);

  // Resonator r falls silent at sample `stop` (its object is destroyed: 003 section 3.3).
  void stop_at(std::size_t r, std::int64_t stop);

  // Mixes every resonator into out, then forgets them.
  ResonatorCounts render(double relative_floor, std::vector<double>& out);

 private:
  struct Injection {
    std::int64_t sample;      // first sample that includes it
    double y1, y2;            // its values at sample - 1 and sample - 2, added to the state
    double envelope;          // |phasor e^{s (t - t0)}| at `sample`
  };
  struct Resonator {
    std::complex<double> pole;
    std::vector<Injection> injections;
    std::int64_t start = 0, end = 0;  // [first injection, envelope below the floor or stop)
    std::int64_t stop = std::numeric_limits<std::int64_t>::max();
  };
  void set_spans(double relative_floor, std::int64_t samples);
  void render_group(const std::vector<const Resonator*>& lanes, std::vector<double>& out, ResonatorCounts& counts) const;

  double rate_hz_;
  std::vector<Resonator> resonators_;
};

}  // namespace clatter::kernels::modal
