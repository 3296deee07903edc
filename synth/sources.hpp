#pragma once
// The rendering loop's view of the world: every event becomes one Impact per object it moves, and
// every sound source (PAN, modal, ground) adds what that impact radiates into its own
// output buffers (one per listener). A source may keep state between impacts (the modal source's
// ringing modes) and finish it after the last.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/rotation.hpp"
#include "io/scene.hpp"
#include "kernels/mesh_contact.hpp"
#include "kernels/rigid_body.hpp"
#include "model/pan_bank.hpp"

namespace clatter::synth {

struct ObjectModel {
  const io::SceneObject* object = nullptr;
  std::size_t index = 0;    // in scene.objects
  kernels::ProxyFit proxy;  // the equivalent ellipsoid (eq. 11, volume matched)
  // The object's own surface for contact (its mesh's frame, shared by objects of one mesh file);
  // null for an object given by numbers, whose contact is the proxy's surface.
  std::shared_ptr<const kernels::MeshContact> contact;
};

// One object's share of one event, in the object's body frame.
struct Impact {
  const ObjectModel* model = nullptr;
  double t_s = 0, tau_s = 0;   // contact start and Hertz duration
  double peak_force_n = 0;     // of the half-sine
  Vec3 direction_body{};       // unit, the force on this object
  Vec3 contact_body_m{};       // contact point relative to the centre of mass
  io::Pose pose;
  // What the ground source needs (synth/ground_source.hpp): whether the other body is the ground
  // (b = "ground", or a James-lab C line), the contact point and this object's impulse, world frame.
  bool on_ground = false;
  bool sustained = false;  // a sustained contact (scene key contact_time_s on a contact event)
  Vec3 point_world_m{};
  Vec3 impulse_world_n_s{};
};

class SoundSource {
 public:
  virtual ~SoundSource() = default;
  virtual std::string name() const = 0;
  // Before the first impact of a render: the scene's objects and the output's length. InputError
  // for an object the source cannot voice.
  virtual void begin(const io::Scene& /*scene*/, const std::vector<ObjectModel>& /*models*/, int /*rate_hz*/) {}
  // Adds the impact's pressure at each listener (world frame) into out[listener] (sample n at
  // n / rate).
  virtual void add(const Impact& impact, const std::vector<Vec3>& listeners_m, int rate_hz,
                   std::vector<std::vector<double>>& out) = 0;
  // After the last impact: whatever the source deferred.
  virtual void finish(std::vector<std::vector<double>>& /*out*/) {}
  // After begin: one line per object outside what the source's bank covers, saying why and what
  // the source does with it instead (docs/synth.md "Coverage").
  virtual std::vector<std::string> coverage(const std::vector<ObjectModel>& /*models*/) const { return {}; }
};

// Acceleration noise from PAN banks. An object given by a mesh that a bank holds as a mesh entry
// (clatter-bank pan-object; the key io::mesh_hash) sounds with its own entry, scaled by
// beta = 1 / its scale, its rotations from its full inertia tensor; every other object with the
// nearest proxy by shape, scaled by beta = a / A (eq. 10).
class PanSource : public SoundSource {
 public:
  // The distance in (B, C) within which an object counts as covered: half the diagonal of the
  // paper's grid (0.0475 m steps at A = 0.5 m), the farthest its 66-proxy bank leaves any shape.
  static constexpr double kCoverage_m = 0.0475 * 0.7071067811865476;

  // `proxy_bank` (-b) gives the proxies (and its mesh entries, if any); `object_banks` (-P) mesh
  // entries. Either may be empty, not both; begin refuses an object neither voices.
  explicit PanSource(const std::string& proxy_bank, const std::vector<std::string>& object_banks = {});
  std::string name() const override { return "pan"; }
  void begin(const io::Scene& scene, const std::vector<ObjectModel>& models, int rate_hz) override;
  void add(const Impact& impact, const std::vector<Vec3>& listeners_m, int rate_hz,
           std::vector<std::vector<double>>& out) override;
  std::vector<std::string> coverage(const std::vector<ObjectModel>& models) const override;
  // After begin: the objects voiced by their own entry.
  std::size_t own_entries() const;

 private:
  struct EntryRef {
    std::size_t bank = 0, entry = 0;
  };
  void add_at(const Impact& impact, const Vec3& listener_world_m, int rate_hz, std::vector<double>& out) const;
  void add_own(const Impact& impact, const EntryRef& own, const Vec3& listener_world_m, int rate_hz, std::vector<double>& out) const;
  std::array<double, 2> shape_at_bank_a(const kernels::ProxyFit& fit) const;  // (B, C)
  std::size_t nearest_proxy(const kernels::ProxyFit& fit) const;            // closest (B, C) at the bank's A

  std::vector<model::PanBank> banks_;  // as read, evaluated in place (kernels/pan); the proxy bank first
  std::vector<std::size_t> proxies_;   // the proxy bank's ellipsoid entries
  std::vector<std::pair<std::string, EntryRef>> keys_;  // every bank's mesh entries, the first of a key kept
  std::vector<std::optional<EntryRef>> own_;            // per scene object (begin)
};

}  // namespace clatter::synth
