#include "sim/impacts.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>

namespace clatter::sim {

ImpactRecorder::ImpactRecorder(double dt_s, const Rules& rules) : dt_s_(dt_s), rules_(rules) {}

void ImpactRecorder::close(Episode& e) {
  io::SceneEvent& ev = e.event;
  for (int d = 0; d < 3; ++d) ev.point_m[d] = e.weighted_point[d] / e.weight;
  if (e.continuation || !(ev.normal_speed_m_s > rules_.min_speed_m_s)) {
    ev.sustained = true;
    ev.contact_time_s = static_cast<double>(e.last_step - e.first_step + 1) * dt_s_;
    ev.normal_speed_m_s = 0;
    ++sustained_;
  } else {
    ++impacts_;
  }
  done_.emplace_back(e.serial, ev);
}

void ImpactRecorder::add_step(double t_s, const std::vector<ContactSample>& contacts) {
  const long long step = std::llround(t_s / dt_s_);
  // Rule 1: episodes without impulse for longer than quiet_s end; pairs left without any go.
  for (auto pair = open_.begin(); pair != open_.end();) {
    auto& episodes = pair->second;
    for (auto it = episodes.begin(); it != episodes.end();) {
      if (static_cast<double>(step - it->last_step - 1) * dt_s_ <= rules_.quiet_s * (1 + 1e-9)) {
        ++it;
        continue;
      }
      close(*it);
      it = episodes.erase(it);
    }
    pair = episodes.empty() ? open_.erase(pair) : std::next(pair);
  }
  for (const ContactSample& c : contacts) {
    auto& episodes = open_[{c.a, c.b}];
    // The nearest open episode of the pair, if near enough (its latest point).
    Episode* e = nullptr;
    double best = rules_.merge_distance_m;
    for (Episode& x : episodes) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (x.last_point[k] - c.point_m[k]) * (x.last_point[k] - c.point_m[k]);
      if (std::sqrt(d2) <= best) best = std::sqrt(d2), e = &x;
    }
    bool continuation = false;
    // Rule 3: an episode that has lasted its window is closed and continued.
    if (e) {
      const double window = e->continuation ? rules_.sustain_window_s : rules_.impact_window_s;
      if (e->first_step != step && static_cast<double>(step - e->first_step + 1) * dt_s_ > window * (1 + 1e-9)) {
        close(*e);
        episodes.erase(episodes.begin() + (e - episodes.data()));
        e = nullptr;
        continuation = true;
      }
    }
    if (!e) {
      Episode n;
      n.serial = serial_++;
      n.continuation = continuation;
      n.first_step = step;
      n.event.t_s = t_s + c.touch_after_s;
      n.event.a = c.a;
      n.event.b = c.b;
      n.event.normal_speed_m_s = c.approach_speed_m_s;
      n.event.pose_a = c.pose_a;
      n.event.pose_b = c.pose_b;
      episodes.push_back(n);
      e = &episodes.back();
    }
    const double w = std::sqrt(c.impulse_n_s[0] * c.impulse_n_s[0] + c.impulse_n_s[1] * c.impulse_n_s[1] +
                               c.impulse_n_s[2] * c.impulse_n_s[2]);
    for (int d = 0; d < 3; ++d) {
      e->event.impulse_n_s[d] += c.impulse_n_s[d];
      e->weighted_point[d] += w * c.point_m[d];
    }
    // A face landing: the episode's normal speed is its fastest point's in its first step.
    if (e->first_step == step) {
      e->event.normal_speed_m_s = std::max(e->event.normal_speed_m_s, c.approach_speed_m_s);
      e->event.t_s = std::min(e->event.t_s, t_s + c.touch_after_s);
    }
    e->weight += w;
    e->last_step = step;
    e->last_point = c.point_m;
  }
}

void ImpactRecorder::add_event(const io::SceneEvent& e) { done_.emplace_back(serial_++, e); }

std::vector<io::SceneEvent> ImpactRecorder::finish() {
  for (auto& [pair, episodes] : open_)
    for (Episode& e : episodes) close(e);
  open_.clear();
  std::sort(done_.begin(), done_.end(), [](const auto& x, const auto& y) {
    return x.second.t_s != y.second.t_s ? x.second.t_s < y.second.t_s : x.first < y.first;
  });
  std::vector<io::SceneEvent> events;
  for (auto& [serial, e] : done_) events.push_back(e);
  done_.clear();
  return events;
}

}  // namespace clatter::sim
