#include "kernels/modal/resonator_bank.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace clatter::kernels::modal {
namespace {

constexpr int kLanes = 8;
using Lanes = std::array<double, kLanes>;

// Samples [n0, n1) of eight resonators in lockstep. The state lives in locals so that it stays in
// registers (out may alias nothing here, but the compiler cannot know that of array members), and
// the lanes are summed as a fixed tree: vectorizable, and the same bits on every CPU. Cloned for
// wider vectors where the CPU has them (chosen at load time); with -ffp-contract=off no clone
// fuses a multiply-add, so every clone rounds the same way.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void step(const Lanes& a1, const Lanes& a2, Lanes& y1_io, Lanes& y2_io, double* out, std::int64_t n0, std::int64_t n1) {
  Lanes y1 = y1_io, y2 = y2_io;
  for (std::int64_t n = n0; n < n1; ++n) {
    Lanes y;
    for (int l = 0; l < kLanes; ++l) {
      y[l] = a1[l] * y1[l] - a2[l] * y2[l];
      y2[l] = y1[l];
      y1[l] = y[l];
    }
    out[n] += ((y[0] + y[1]) + (y[2] + y[3])) + ((y[4] + y[5]) + (y[6] + y[7]));
  }
  y1_io = y1;
  y2_io = y2;
}

}  // namespace

std::size_t ResonatorBank::add(std::complex<double> pole) {
  if (!(pole.real() <= 0) || !std::isfinite(pole.imag())) throw std::invalid_argument("ResonatorBank: a pole must not grow");
  resonators_.push_back({pole, {}, 0, 0});
  return resonators_.size() - 1;
}

void ResonatorBank::stop_at(std::size_t r, std::int64_t stop) { resonators_.at(r).stop = std::min(resonators_.at(r).stop, stop); }

void ResonatorBank::excite(std::size_t r, double t0, const HalfSineResponse& q, double weight, std::vector<double>& out) {
  const auto samples = static_cast<std::int64_t>(out.size());
  const auto first = static_cast<std::int64_t>(std::ceil(t0 * rate_hz_));
  const auto after = static_cast<std::int64_t>(std::ceil((t0 + q.contact_time_s()) * rate_hz_));
  const std::int64_t begin = std::max<std::int64_t>(first, 0), end = std::min(after, samples);
  if (end > begin)
    q.add_contact_samples(static_cast<double>(begin) / rate_hz_ - t0, 1 / rate_hz_, static_cast<std::size_t>(end - begin), weight,
                          out.data() + begin);
  if (after < samples) inject(r, after, weight * q.free_phasor(), t0);
}

void ResonatorBank::inject(std::size_t r, std::int64_t first, std::complex<double> phasor, double t0) {
  Resonator& res = resonators_.at(r);
  auto value = [&](std::int64_t n) { return (phasor * std::exp(res.pole * (static_cast<double>(n) / rate_hz_ - t0))).imag(); };
  const double envelope = std::abs(phasor) * std::exp(res.pole.real() * (static_cast<double>(first) / rate_hz_ - t0));
  res.injections.push_back({first, value(first - 1), value(first - 2), envelope});
}

// Start and end of every resonator. The envelope bound after an injection is the sum of each
// injection's envelope, decayed: the true envelope of the sum of sinusoids never exceeds it, so
// no resonator stops while it can still be above the floor.
void ResonatorBank::set_spans(double relative_floor, std::int64_t samples) {
  std::vector<double> last_bound(resonators_.size(), 0.0);
  double loudest = 0;
  for (std::size_t i = 0; i < resonators_.size(); ++i) {
    Resonator& r = resonators_[i];
    std::stable_sort(r.injections.begin(), r.injections.end(), [](const Injection& a, const Injection& b) { return a.sample < b.sample; });
    double bound = 0;
    std::int64_t at = r.injections.empty() ? 0 : r.injections.front().sample;
    for (const Injection& inj : r.injections) {
      bound = bound * std::exp(r.pole.real() * static_cast<double>(inj.sample - at) / rate_hz_) + inj.envelope;
      at = inj.sample;
      loudest = std::max(loudest, bound);
    }
    last_bound[i] = bound;
  }
  const double floor = relative_floor * loudest;
  for (std::size_t i = 0; i < resonators_.size(); ++i) {
    Resonator& r = resonators_[i];
    if (r.injections.empty()) continue;
    r.start = r.injections.front().sample;
    const std::int64_t last = r.injections.back().sample;
    const double decay_1_s = -r.pole.real();
    double alive = static_cast<double>(samples);  // an undamped mode rings to the end
    if (!(last_bound[i] > floor))
      alive = 0;
    else if (decay_1_s > 0 && floor > 0)
      alive = std::min(alive, std::ceil(std::log(last_bound[i] / floor) / decay_1_s * rate_hz_));
    r.end = std::min({samples, r.stop, last + 1 + static_cast<std::int64_t>(alive)});
  }
}

void ResonatorBank::render_group(const std::vector<const Resonator*>& lanes, std::vector<double>& out, ResonatorCounts& counts) const {
  Lanes a1{}, a2{}, y1{}, y2{};  // idle lanes: a1 = a2 = 0 keeps them at 0
  struct Event {
    std::int64_t sample;
    int lane;
    const Injection* injection;
  };
  std::vector<Event> events;
  std::int64_t begin = std::numeric_limits<std::int64_t>::max(), end = 0;
  for (std::size_t l = 0; l < lanes.size(); ++l) {
    const Resonator& r = *lanes[l];
    const double dt = 1 / rate_hz_, decay = std::exp(r.pole.real() * dt);
    a1[l] = 2 * decay * std::cos(r.pole.imag() * dt);
    a2[l] = decay * decay;
    begin = std::min(begin, r.start);
    end = std::max(end, r.end);
    counts.mode_samples += static_cast<std::uint64_t>(r.end - r.start);
    for (const Injection& inj : r.injections)
      if (inj.sample < r.end) events.push_back({inj.sample, static_cast<int>(l), &inj});
    events.push_back({r.end, static_cast<int>(l), nullptr});  // the lane falls silent
  }
  if (begin >= end) return;
  std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.sample < b.sample; });
  std::int64_t n = begin;
  for (const Event& e : events) {
    step(a1, a2, y1, y2, out.data(), n, e.sample);
    n = e.sample;
    const auto l = static_cast<std::size_t>(e.lane);
    if (e.injection) {
      y1[l] += e.injection->y1;
      y2[l] += e.injection->y2;
    } else {
      a1[l] = a2[l] = y1[l] = y2[l] = 0;
    }
  }
  step(a1, a2, y1, y2, out.data(), n, end);
  counts.stepped_samples += static_cast<std::uint64_t>(kLanes) * static_cast<std::uint64_t>(end - begin);
}

ResonatorCounts ResonatorBank::render(double relative_floor, std::vector<double>& out) {
  set_spans(relative_floor, static_cast<std::int64_t>(out.size()));
  std::vector<const Resonator*> order;
  ResonatorCounts counts;
  for (const Resonator& r : resonators_) {
    counts.injections += r.injections.size();
    if (r.end > r.start) order.push_back(&r);
  }
  counts.resonators = order.size();
  // Lanes that start together share a group; sorting by end within equal starts is a tie-break.
  std::stable_sort(order.begin(), order.end(), [](const Resonator* a, const Resonator* b) {
    return a->start != b->start ? a->start < b->start : a->end < b->end;
  });
  for (std::size_t i = 0; i < order.size(); i += kLanes) {
    const std::vector<const Resonator*> lanes(order.begin() + static_cast<std::ptrdiff_t>(i),
                                              order.begin() + static_cast<std::ptrdiff_t>(std::min(order.size(), i + kLanes)));
    render_group(lanes, out, counts);
  }
  resonators_.clear();
  return counts;
}

}  // namespace clatter::kernels::modal
