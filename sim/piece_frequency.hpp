#pragma once
// The base frequency clatter-sim writes for a fracture piece (003 section 5.4 scales the modal
// proxy to it).
#include <vector>

#include "core/vec3.hpp"
#include "model/material.hpp"

namespace clatter::sim {

// A fracture piece's lowest free-vibration frequency, of its convex hull: its own surface is too
// fine for a quick solve. The hull is taken over the surface's vertices snapped to a grid of 5 % of
// the piece's thinnest extent (surface_m in its principal frame), at most 32 vertices: TetGen 1.5 aborts (an assertion, not an error)
// on some hulls with near-duplicate vertices and sliver faces, which the fine fracture surfaces
// make. (A grid of 1 % of the diagonal was coarser than a window's 4 mm pieces are thick: their
// hull collapsed onto a plane, non-manifold.) 0 when the hull cannot be solved (a bad hull, no
// convergence): the synthesizer then computes it from the piece's mesh.
double piece_base_frequency_hz(const std::vector<Vec3>& surface_m, double volume_m3, const model::Material& material);

}  // namespace clatter::sim
