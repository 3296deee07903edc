#pragma once
// A small valid PAN bank and task result (3 directions, 2 radii: 3 values per coefficient, wavelet length 16), the starting
// point the HDF5 harnesses mutate. Written through Clatter's own writers, so the templates follow
// the format as the code defines it.
#include <string>

#include "model/pan_bank.hpp"

namespace clatter::fuzz {

inline constexpr std::size_t kTemplateValues = 3;  // the far field and one residual per radius
inline constexpr std::uint32_t kTemplateLength = 16;
inline constexpr std::size_t kTemplateDirections = 3;

inline model::SparseTerms template_terms(std::uint32_t first) {
  return {{first, first + 3, first + 7}, {0.5f, -0.25f, 0.0625f, 1.0f, 0.125f, -0.5f, -2.0f, 0.75f, 0.25f}};
}

inline model::PanBank template_bank() {
  model::PanBank bank;
  auto& h = bank.header;
  h.c_m_s = 343.2;
  h.rho_kg_m3 = 1.2041;
  h.h_s = 5e-4;
  h.dt_s = 1.0 / 24000;
  h.t_first_s = -0.003;
  h.epsilon = 0.01;
  h.length = kTemplateLength;
  h.radii_m = {0.7, 0.85};
  h.directions = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  h.triangles = {{0, 1, 2}};
  for (int p = 0; p < 2; ++p) {
    model::PanProxy proxy;
    proxy.b_m = 0.5 - 0.1 * p;
    proxy.c_m = 0.2;
    for (int f : {0, 2}) proxy.fields[static_cast<std::size_t>(f)] = {template_terms(0), template_terms(2), template_terms(8)};
    bank.proxies.push_back(proxy);
  }
  bank.sweep.sweep_id = "0123456789abcdef";
  bank.sweep.tasks_total = 12;
  bank.sweep.missing = {"p001-f2"};
  return bank;
}

inline model::PanTaskResult template_task() {
  model::PanTaskResult t;
  t.proxy = 1;
  t.b_m = 0.4;
  t.c_m = 0.2;
  t.field = 3;
  t.directions = {template_terms(0), template_terms(2), template_terms(8)};
  return t;
}

}  // namespace clatter::fuzz
