#pragma once
// A generated scene's object: the uniform solid ellipsoid with semi-axes a, b, c along the body
// axes (I_x = m (b^2 + c^2) / 5, ...), for the synthesizer's benchmark scenes.
#include <numbers>
#include <string>

#include "io/scene.hpp"

namespace clatter::bench {

inline io::SceneObject solid_ellipsoid(int id, double a_m, double b_m, double c_m, double rho_kg_m3, const std::string& material) {
  io::SceneObject o;
  o.id = id;
  o.volume_m3 = 4.0 / 3.0 * std::numbers::pi * a_m * b_m * c_m;
  o.mass_kg = rho_kg_m3 * o.volume_m3;
  const double f = o.mass_kg / 5;
  o.inertia_kg_m2 = {{{f * (b_m * b_m + c_m * c_m), 0, 0}, {0, f * (a_m * a_m + c_m * c_m), 0}, {0, 0, f * (a_m * a_m + b_m * b_m)}}};
  o.material = material;
  return o;
}

}  // namespace clatter::bench
