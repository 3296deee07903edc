#pragma once
// The scene as synthesis needs it: read in either input form, with every object's mass properties
// known, including those of objects given by a closed triangle mesh.
#include <string>

#include "io/scene.hpp"

namespace clatter::synth {

// impulses_path empty: scene_path is a native scene. Otherwise scene_path is the side file of a
// James-lab impulse file (docs/scene-format.md). An object given by a mesh gets the mass, volume,
// inertia (about the centre of mass, in the mesh's axes) and rest_centre_m of the uniform solid it
// bounds, and keeps the mesh (SceneObject::mesh, and its area) for contact and the modal energy
// rule; with base_frequencies, also its lowest free-vibration frequency (unless the scene gives
// it), from a FEM of that solid in its material (kernels/fem/lowest_mode.hpp), once per mesh file
// and material. InputError names the file and field or line.
io::Scene load_scene(const std::string& scene_path, const std::string& impulses_path = "", bool base_frequencies = false);


// The two steps of load_scene after reading, for a scene read otherwise (io::parse_scene): every
// object given by a mesh file gets its mesh and mass properties (once per file), and then, for
// modal sound, each such object without a given base frequency its FEM's lowest mode.
void resolve_meshes(io::Scene& scene);
void add_base_frequencies(io::Scene& scene);

}  // namespace clatter::synth
