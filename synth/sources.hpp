#pragma once
// The rendering loop's view of the world: every event becomes one Impact per object it moves, and
// every sound source (PAN now; modal and ground later) adds what that impact radiates into the
// same output buffers.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/rotation.hpp"
#include "io/scene.hpp"
#include "kernels/rigid_body.hpp"
#include "model/pan_bank.hpp"

namespace clatter::synth {

struct ObjectModel {
  const io::SceneObject* object = nullptr;
  kernels::ProxyFit proxy;  // the equivalent ellipsoid (eq. 11, volume matched)
};

// One object's share of one event, in the object's body frame.
struct Impact {
  const ObjectModel* model = nullptr;
  double t_s = 0, tau_s = 0;   // contact start and Hertz duration
  double peak_force_n = 0;     // of the half-sine
  Vec3 direction_body{};       // unit, the force on this object
  Vec3 contact_body_m{};       // contact point relative to the centre of mass
  io::Pose pose;
};

class SoundSource {
 public:
  virtual ~SoundSource() = default;
  virtual std::string name() const = 0;
  // Adds the impact's pressure at the listener (world frame) into `out` (sample n at n / rate).
  virtual void add(const Impact& impact, const Vec3& listener_world_m, int rate_hz, std::vector<double>& out) const = 0;
};

// Acceleration noise from a PAN bank: nearest proxy by shape, scaled by beta = a / A (eq. 10).
class PanSource : public SoundSource {
 public:
  explicit PanSource(const std::string& bank_path);
  std::string name() const override { return "pan"; }
  void add(const Impact& impact, const Vec3& listener_world_m, int rate_hz, std::vector<double>& out) const override;
 private:
  std::size_t nearest_proxy(const kernels::ProxyFit& fit) const;  // closest (B, C) at the bank's A

  model::PanBank bank_;  // as read, evaluated in place (kernels/pan)
};

}  // namespace clatter::synth
