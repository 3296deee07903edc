#pragma once
// The synthesizer's one loop: events in time order, each split into one Impact per object it
// moves (Hertz duration, half-sine force), fed to every sound source for every listener.
#include <array>
#include <memory>
#include <vector>

#include "io/scene.hpp"
#include "synth/sources.hpp"

namespace clatter::synth {

struct RenderOptions {
  int rate_hz = 44100;
  double tail_s = 0.1;  // rendered after the last event when the scene gives no duration
  // Sustained contacts (a resting or sliding force, scene key contact_time_s on a contact event)
  // longer than this are not rendered: their acceleration noise is ~35 dB below the impacts'
  // (measured on the rock slide, docs/synth.md), and the modal model (|p_k| at the mode's own
  // frequency) holds for ringing, not for the slow deflection such a force makes, whose sound it
  // would overstate. Counted in RenderStats::skipped_sustained.
  double max_sustained_s = 0.01;
};

struct RenderStats {
  std::size_t impacts = 0;          // object-side impacts rendered
  std::size_t skipped_inactive = 0; // impacts on objects not yet created or already destroyed
  std::size_t fracture_impacts = 0; // of `impacts`, fracture impulses (003 section 3.3)
  std::size_t sustained_impacts = 0;  // of `impacts`, sustained contacts (resting, sliding)
  std::size_t skipped_sustained = 0;  // sustained-contact events longer than max_sustained_s, not rendered
  // Hertz contacts taken on an object's own mesh, by kernels::ContactFeature: smooth (or flat), edge,
  // corner (one per object side with a mesh).
  std::array<std::size_t, 3> mesh_contacts{};
  std::vector<std::vector<std::string>> coverage;  // per source: objects outside its bank's coverage
};

// stems[s][l]: the samples of source s at listener l. Throws InputError (naming the scene file,
// object or event) for an object whose inertia cannot be a rigid body's, a listener inside an
// object, an object a source cannot voice, or a contact point far from a mesh object's surface. A
// fracture event's impulse acts over its given contact_time_s on piece a alone; every other
// event's over the Hertz time of the pair, whose radii come from the objects' meshes where they
// have one, else from their proxies (docs/synth.md "Contact from the object's surface").
std::vector<std::vector<std::vector<double>>> render_scene(const io::Scene& scene,
                                                           const std::vector<SoundSource*>& sources,
                                                           const RenderOptions& options, RenderStats* stats = nullptr);

// The objects' proxies (eq. 11) and, for objects given by a mesh, their contact surfaces
// (kernels/mesh_contact.hpp, one per mesh file); InputError names the object.
std::vector<ObjectModel> object_models(const io::Scene& scene, const std::string& scene_path);

}  // namespace clatter::synth
