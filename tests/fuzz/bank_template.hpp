#pragma once
// A small valid PAN bank and task result (the layout of 2 divisions, 6 directions, once refined to
// 15; 2 radii: 3 values per coefficient; wavelet length 16), the starting point the HDF5 harnesses
// mutate. Written through Clatter's own writers, so the templates follow the format as the code
// defines it; the direction sets are kernels::pan::DirectionMesh(2, 1) before and after split(0),
// written out here because the harnesses link io only.
#include <string>

#include "model/pan_bank.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace clatter::fuzz {

inline constexpr std::size_t kTemplateValues = 3;  // the far field and one residual per radius
inline constexpr std::uint32_t kTemplateLength = 16;
inline constexpr std::int32_t kTemplateDivisions = 2, kTemplateLevels = 1;
inline constexpr std::size_t kTemplateTaskDirections = 15;  // the refined set's

inline model::SparseTerms template_terms(std::uint32_t first) {
  return {{first, first + 3, first + 7}, {0.5f, -0.25f, 0.0625f, 1.0f, 0.125f, -0.5f, -2.0f, 0.75f, 0.25f}};
}

inline model::PanField template_field(bool refined) {
  model::PanField f;
  f.directions.vertices = {{0, 0}, {0, 2}, {0, 4}, {2, 0}, {2, 2}, {4, 0}};
  f.directions.elements = {{0, 5, 2, 3, 4, 1}};
  f.directions.first_child = {-1};
  if (refined) {
    f.directions.vertices.insert(f.directions.vertices.end(), {{1, 0}, {1, 1}, {0, 1}, {3, 0}, {3, 1}, {2, 1}, {1, 2}, {1, 3}, {0, 3}});
    f.directions.elements.insert(f.directions.elements.end(), {{0, 3, 1, 6, 7, 8}, {3, 5, 4, 9, 10, 11},
                                                               {1, 4, 2, 12, 13, 14}, {4, 1, 3, 12, 7, 11}});
    f.directions.first_child = {1, -1, -1, -1, -1};
  }
  for (std::size_t v = 0; v < f.directions.vertices.size(); ++v) f.terms.push_back(template_terms(static_cast<std::uint32_t>(v % 3 * 4)));
  return f;
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
  h.divisions = kTemplateDivisions;
  h.max_levels = kTemplateLevels;
  for (int p = 0; p < 2; ++p) {
    model::PanProxy proxy;
    proxy.b_m = 0.5 - 0.1 * p;
    proxy.c_m = 0.2;
    for (int f : {0, 2}) proxy.fields[static_cast<std::size_t>(f)] = template_field((f == 0) == (p == 0));
    bank.proxies.push_back(proxy);
  }
  model::PanProxy mesh;  // a mesh entry (pan-object): /meshes
  mesh.mesh.key = "8da2256c9343da99";
  mesh.mesh.scale = 41.5;
  mesh.mesh.centre_of_mass_m = {0, 0, 0.001};
  mesh.mesh.support_points_m = {{0.5, 0, 0.04}, {0, 0.5, -0.04}, {-0.5, 0, 0.04}};
  mesh.fields[2] = template_field(true);
  bank.proxies.push_back(mesh);
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
  t.fit = template_field(true);
  return t;
}

// What the evaluator's locate (kernels/pan/direction_mesh.hpp) indexes without checks, restated: a
// solved field's set holds the layout's roots, its nodes and children are in range (children after
// their parent), its lattice points in the triangle, and one set of terms per vertex whose indices
// ascend below the length, with `values` values each.
inline void check_field(const model::PanField& f, std::int32_t divisions, std::int32_t lattice, std::size_t values,
                        std::uint32_t length) {
  const auto& s = f.directions;
  if (f.terms.size() != s.vertices.size()) broken("terms per direction");
  if (f.terms.empty()) {
    if (!s.elements.empty() || !s.first_child.empty()) broken("elements of an unsolved field");
    return;
  }
  if (s.elements.size() < static_cast<std::size_t>(divisions / 2 * (divisions / 2))) broken("fewer elements than roots");
  if (s.first_child.size() != s.elements.size()) broken("children per element");
  for (const auto& p : s.vertices)
    if (p.a < 0 || p.b < 0 || p.a + p.b > lattice) broken("lattice point outside the triangle");
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    for (std::int32_t n : s.elements[e])
      if (n < 0 || static_cast<std::size_t>(n) >= s.vertices.size()) broken("element node out of range");
    const std::int32_t c = s.first_child[e];
    if (c != -1 && (c <= static_cast<std::int64_t>(e) || static_cast<std::size_t>(c) + 4 > s.elements.size()))
      broken("child out of range or before its parent");
  }
  for (const auto& d : f.terms) {
    if (d.value.size() != d.index.size() * values) broken("values per index");
    for (std::size_t e = 0; e < d.index.size(); ++e)
      if (d.index[e] >= length || (e > 0 && d.index[e] <= d.index[e - 1])) broken("index order/range");
  }
}

}  // namespace clatter::fuzz
