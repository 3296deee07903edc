#include "io/pan_bank.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "io/h5.hpp"
#include "io/pan_mesh_bodies.hpp"
#include "io/provenance.hpp"
#include "io/sweep_files.hpp"

namespace clatter::io {

using model::PanBank;
using model::PanBankHeader;
using model::PanProxy;
using model::PanTaskResult;
using model::SparseTerms;

namespace {

// ---- The hierarchical coding of a direction set's vertices (docs/bank-format.md) ----
// A vertex a split made is stored as its values minus the quadratic interpolation of its parent
// element's six nodes at its position (decoded values, so writer and reader predict alike), with
// the coefficients whose difference is small dropped: where the parent already interpolates the
// field well, a refined direction costs little.

// The thresholds of the coding, as fractions of the bank's epsilon: a made vertex's differences,
// and its decoded coefficients, below kCodedEpsilon epsilon of its peak are dropped. Measured on
// the demo bank (docs/pan.md, "Adaptive directions"): at 1 the held-out errors grew by up to
// 1.5 points (the elongated proxy's field 4: 1.3 -> 2.5 %); at 1/4 they are within 0.3 points of
// the uncoded bank's, for a bank 25 % larger than at 1 and half the uncoded one.
constexpr double kCodedEpsilon = 0.25;
// A made vertex's peak in that rule is at least this share of its field's largest: a direction far
// weaker than the field's strongest is coded against it. The values are q, the field over its
// symmetry zeros (format 5), whose largest lie near the planes where p is small; at a tenth (the
// rule until 2026-12-07) the cigar's swing lost 6.5 % in directions 1-3 % as loud as its loudest,
// coded against a floor far above them; at a hundredth it holds 2.9 % there for 9 % more bytes
// (docs/pan.md, "The refinement's floor").
constexpr double kCodedFloor = 0.01;

// Quadratic weights of a parent's six nodes at child c's node k (model::kChildCorners).
std::array<double, 6> split_weights(std::size_t c, std::size_t k) {
  static constexpr std::array<std::array<double, 3>, 6> kParent{
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}}};
  auto corner = [&](std::size_t i) { return kParent[static_cast<std::size_t>(model::kChildCorners[c][i])]; };
  std::array<double, 3> l = corner(k % 3);
  if (k >= 3)
    for (std::size_t i = 0; i < 3; ++i) l[i] = 0.5 * (corner(k - 3)[i] + corner((k - 2) % 3)[i]);
  return {l[0] * (2 * l[0] - 1), l[1] * (2 * l[1] - 1), l[2] * (2 * l[2] - 1), 4 * l[0] * l[1], 4 * l[1] * l[2],
          4 * l[2] * l[0]};
}

// How vertex v is predicted: from element `parent`'s nodes with `weight`, or not (parent -1: a
// vertex of the layout).
struct Prediction {
  std::int32_t parent = -1;
  std::array<double, 6> weight{};
};

// Per vertex; throws std::invalid_argument unless the vertices are numbered as they were made (the
// layout's first, then each split's new nodes in order), every parent node made before its child.
std::vector<Prediction> predictions(const model::PanDirections& set, std::size_t roots) {
  const auto& el = set.elements;
  std::size_t made = 0;  // vertices 0 .. made - 1 are known
  for (std::size_t e = 0; e < roots; ++e)
    for (std::int32_t n : el.at(e)) made = std::max(made, static_cast<std::size_t>(n) + 1);
  std::vector<Prediction> out(set.vertices.size());
  std::vector<std::pair<std::int32_t, std::size_t>> splits;  // (first child, parent) in the order made
  for (std::size_t e = 0; e < set.first_child.size(); ++e)
    if (set.first_child[e] >= 0) splits.push_back({set.first_child[e], e});
  std::sort(splits.begin(), splits.end());
  for (const auto& [first, e] : splits)
    for (std::size_t c = 0; c < 4; ++c)
      for (std::size_t k = 0; k < 6; ++k) {
        const auto v = static_cast<std::size_t>(el.at(static_cast<std::size_t>(first) + c)[k]);
        if (v < made) continue;
        if (v != made) throw std::invalid_argument("vertices are not numbered in the order the splits made them");
        for (std::int32_t n : el[e])
          if (static_cast<std::size_t>(n) >= v) throw std::invalid_argument("a parent node made after its child");
        out[v] = {static_cast<std::int32_t>(e), split_weights(c, k)};
        ++made;
      }
  if (made != set.vertices.size()) throw std::invalid_argument("vertices that no split made");
  return out;
}

// values[v] = prediction from the decoded values of its parent's nodes (dense, T x values), or 0.
void predict(const model::PanDirections& set, const Prediction& p, const std::vector<std::vector<double>>& decoded,
             std::vector<double>& values) {
  std::fill(values.begin(), values.end(), 0.0);
  if (p.parent < 0) return;
  const auto& nodes = set.elements[static_cast<std::size_t>(p.parent)];
  for (std::size_t i = 0; i < 6; ++i) {
    const auto& parent = decoded[static_cast<std::size_t>(nodes[i])];
    for (std::size_t n = 0; n < values.size(); ++n) values[n] += p.weight[i] * parent[n];
  }
}

// The largest |R p| one coefficient's values give: the far field F (x[0]) or F + D_k at radius k.
double rp_peak(const double* x, std::size_t n_values) {
  double m = std::abs(x[0]);
  for (std::size_t k = 1; k < n_values; ++k) m = std::max(m, std::abs(x[0] + x[k]));
  return m;
}

std::size_t layout_roots(std::int32_t divisions) {
  return static_cast<std::size_t>(divisions / 2) * static_cast<std::size_t>(divisions / 2);
}

// The bank's coefficients as stored: the CSR of quantized values, a row per vertex of every field's
// direction set in (proxy, field, vertex) order.
struct PackedCoefficients {
  std::vector<std::uint32_t> offsets{0};
  std::vector<std::uint16_t> delta;
  std::vector<std::int16_t> quantized;
  std::vector<float> scale;
};

PackedCoefficients pack_coefficients(const PanBank& bank) {
  const PanBankHeader& h = bank.header;
  const std::size_t n_values = h.values(), dense_size = h.length * n_values;
  PackedCoefficients out;
  auto& [offsets, delta, quantized, scale] = out;
  for (const auto& proxy : bank.proxies) {
    for (int o = 0; o < proxy.octants(); ++o)
    for (int f = 1; f <= 6; ++f) {
      const model::PanField& field = proxy.field(f, o);
      const auto& set = field.directions;
      if (field.terms.size() != set.vertices.size())
        throw std::invalid_argument("PAN bank: a field's terms are not one per vertex of its direction set");
      if (!field.solved()) continue;
      const auto pred = predictions(set, layout_roots(h.divisions));
      std::vector<double> peak(field.terms.size(), 0.0), x(n_values);  // per vertex, rp_peak's largest
      for (std::size_t v = 0; v < field.terms.size(); ++v)
        for (std::size_t e = 0; e < field.terms[v].index.size(); ++e) {
          for (std::size_t k = 0; k < n_values; ++k) x[k] = field.terms[v].value[e * n_values + k];
          peak[v] = std::max(peak[v], rp_peak(x.data(), n_values));
        }
      const double field_peak = *std::max_element(peak.begin(), peak.end());
      std::vector<std::vector<double>> decoded(field.terms.size());
      std::vector<double> coded(dense_size);
      for (std::size_t v = 0; v < field.terms.size(); ++v) {
        const SparseTerms& t = field.terms[v];
        predict(set, pred[v], decoded, coded);
        decoded[v] = coded;  // the prediction; the stored differences are added below
        for (double& c : coded) c = -c;
        for (std::size_t e = 0; e < t.index.size(); ++e)
          for (std::size_t k = 0; k < n_values; ++k) coded[t.index[e] * n_values + k] += t.value[e * n_values + k];
        // Kept: a root vertex's fitted coefficients; a made vertex's where a difference reaches
        // kCodedEpsilon times epsilon times its own peak |R p|, or kCodedFloor of the field's.
        std::vector<std::uint32_t> kept;
        if (pred[v].parent < 0) {
          kept = t.index;
        } else {
          const double small = kCodedEpsilon * h.epsilon * std::max(peak[v], kCodedFloor * field_peak);
          for (std::uint32_t j = 0; j < h.length; ++j)
            for (std::size_t k = 0; k < n_values; ++k)
              if (std::abs(coded[j * n_values + k]) >= small && std::abs(coded[j * n_values + k]) > 0) {
                kept.push_back(j);
                break;
              }
        }
        // Quantization step matched to the fit: coefficients under epsilon * max were dropped, so
        // a step of epsilon * max / 16 (error <= epsilon * max / 32) adds little to the far field,
        // and small integers deflate well. A residual's step is epsilon * max / 4 of the larger of
        // its own and the far field's peak: it is an error in R p = F + D, which the cubic in 1/R
        // spreads over at most four residuals; measured on the demo bank, /4 instead of /16 moved
        // the held-out errors by under 0.1 % and saved 17 % (docs/pan.md). The peaks are the
        // vertex's values'; the 16-bit range bounds the step from below (for a made vertex, by its
        // differences).
        std::vector<float> value_peak(n_values, 0.0f), coded_peak(n_values, 0.0f);
        for (std::size_t k = 0; k < n_values; ++k) {
          for (std::size_t e = 0; e < t.index.size(); ++e)
            value_peak[k] = std::max(value_peak[k], std::abs(t.value[e * n_values + k]));
          for (std::uint32_t j : kept) coded_peak[k] = std::max(coded_peak[k], static_cast<float>(std::abs(coded[j * n_values + k])));
        }
        for (std::size_t k = 0; k < n_values; ++k)
          scale.push_back(std::max({value_peak[k] / 32767.0f, coded_peak[k] / 32767.0f,
                                    static_cast<float>(h.epsilon) * std::max(value_peak[k], value_peak[0]) / (k == 0 ? 16.0f : 4.0f)}));
        const float* sc = &scale[scale.size() - n_values];
        std::uint32_t previous = 0;
        for (std::size_t e = 0; e < kept.size(); ++e) {
          const std::uint32_t j = kept[e];
          delta.push_back(static_cast<std::uint16_t>(e == 0 ? j : j - previous));
          previous = j;
          for (std::size_t k = 0; k < n_values; ++k) {
            const auto q = static_cast<std::int16_t>(sc[k] > 0 ? std::lround(coded[j * n_values + k] / sc[k]) : 0);
            quantized.push_back(q);
            decoded[v][j * n_values + k] += static_cast<double>(q) * static_cast<double>(sc[k]);
          }
        }
        offsets.push_back(static_cast<std::uint32_t>(delta.size()));
      }
    }
  }
  return out;
}

// Decodes one field's rows of `c`, from `row` on (advanced past them), into out.terms, out.directions
// given: a layout vertex's stored coefficients as they are; a made vertex's prediction plus its
// differences, of which the evaluator gets the coefficients the fit's rule keeps (kernels/pan/fit.hpp)
// at kCodedEpsilon times epsilon: R p at some radius or at infinity (F + D_k, or F) reaching that
// fraction of its peak, or of kCodedFloor of the field's. InputError prefixed by `where`.
void unpack_field(const PanBankHeader& h, const PackedCoefficients& c, std::size_t& row, model::PanField& out,
                  const std::string& where) {
  if (out.directions.vertices.empty()) return;
  const std::size_t n_values = h.values(), dense_size = h.length * n_values;
  std::vector<Prediction> pred;
  try {
    pred = predictions(out.directions, layout_roots(h.divisions));
  } catch (const std::invalid_argument& e) {
    throw InputError(where + ": " + e.what());
  }
  std::vector<std::vector<double>> decoded(out.directions.vertices.size());
  out.terms.assign(out.directions.vertices.size(), {});
  for (std::size_t v = 0; v < out.terms.size(); ++v, ++row) {
    if (row + 1 >= c.offsets.size() || c.offsets[row] > c.offsets[row + 1] || c.offsets[row + 1] > c.delta.size())
      throw InputError(where + ": '/coefficients/offsets' is not a valid partition of " + std::to_string(c.delta.size()) +
                       " coefficients (row " + std::to_string(row) + ")");
    auto& terms = out.terms[v];
    std::vector<double>& dense = decoded[v];
    dense.resize(dense_size);
    predict(out.directions, pred[v], decoded, dense);
    std::uint32_t j = 0;
    for (std::uint32_t e = c.offsets[row]; e < c.offsets[row + 1]; ++e) {
      j = e == c.offsets[row] ? c.delta[e] : j + c.delta[e];
      if (j >= h.length || (e > c.offsets[row] && c.delta[e] == 0))
        throw InputError(where + ": '/coefficients/index_delta' gives coefficient index " + std::to_string(j) +
                         " outside [0, " + std::to_string(h.length) + ") or repeated");
      if (pred[v].parent < 0) terms.index.push_back(j);
      for (std::size_t k = 0; k < n_values; ++k) {
        const std::int16_t q = c.quantized[e * n_values + k];
        const float sc = c.scale[row * n_values + k];
        dense[j * n_values + k] += static_cast<double>(q) * static_cast<double>(sc);
        if (pred[v].parent < 0) terms.value.push_back(static_cast<float>(q) * sc);
      }
    }
  }
  std::vector<double> peak(out.terms.size(), 0.0);
  for (std::size_t v = 0; v < out.terms.size(); ++v)
    for (std::uint32_t n = 0; n < h.length; ++n) peak[v] = std::max(peak[v], rp_peak(&decoded[v][n * n_values], n_values));
  const double field_peak = *std::max_element(peak.begin(), peak.end());
  for (std::size_t v = 0; v < out.terms.size(); ++v) {
    if (pred[v].parent < 0) continue;
    const double small = kCodedEpsilon * h.epsilon * std::max(peak[v], kCodedFloor * field_peak);
    auto& terms = out.terms[v];
    for (std::uint32_t n = 0; n < h.length; ++n) {
      const double* x = &decoded[v][n * n_values];
      if (rp_peak(x, n_values) < small || rp_peak(x, n_values) == 0) continue;
      terms.index.push_back(n);
      for (std::size_t k = 0; k < n_values; ++k) terms.value.push_back(static_cast<float>(x[k]));
    }
  }
}

// Direction sets (model::PanDirections) as stored: one CSR of vertices and one of elements over the
// sets, in (proxy, field) order for a bank; element node and child indices are local to their set.
void write_direction_sets(File& file, const std::string& group, const std::vector<const model::PanDirections*>& sets,
                          std::int32_t lattice) {
  std::vector<std::uint32_t> vertex_offsets{0}, element_offsets{0};
  std::vector<std::int32_t> points, elements, first_child;
  std::vector<float> unit;  // for readers without the lattice rule (plots): float is plenty
  for (const auto* set : sets) {
    for (const auto& v : set->vertices) {
      points.insert(points.end(), {v.a, v.b});
      const double x = v.a, y = v.b, z = lattice - v.a - v.b, n = std::sqrt(x * x + y * y + z * z);
      unit.insert(unit.end(), {static_cast<float>(x / n), static_cast<float>(y / n), static_cast<float>(z / n)});
    }
    for (const auto& e : set->elements) elements.insert(elements.end(), e.begin(), e.end());
    first_child.insert(first_child.end(), set->first_child.begin(), set->first_child.end());
    vertex_offsets.push_back(static_cast<std::uint32_t>(points.size() / 2));
    element_offsets.push_back(static_cast<std::uint32_t>(first_child.size()));
  }
  const std::size_t nv = points.size() / 2, ne = first_child.size();
  write_dataset<std::uint32_t>(file, group + "/vertex_offsets", vertex_offsets, {vertex_offsets.size()}, "1", true);
  write_dataset<std::int32_t>(file, group + "/lattice", points, {nv, 2}, "1", true);
  write_dataset<float>(file, group + "/unit", unit, {nv, 3}, "1", true);
  write_dataset<std::uint32_t>(file, group + "/element_offsets", element_offsets, {element_offsets.size()}, "1", true);
  write_dataset<std::int32_t>(file, group + "/elements", elements, {ne, 6}, "1", true);
  write_dataset<std::int32_t>(file, group + "/first_child", first_child, {ne}, "1", true);
}

// Reads n_sets direction sets and checks what locate() relies on (kernels/pan/direction_mesh.hpp):
// partitions, lattice points in the triangle, node indices in range, children after their parent
// and inside the set, the layout's roots present. That each set is exactly a refinement of the
// layout is the kernels' replay (kernels::pan::check_direction_sets), which the tools run on load.
std::vector<model::PanDirections> read_direction_sets(const File& file, const std::string& group, std::size_t n_sets,
                                                      std::int32_t divisions, std::int32_t lattice) {
  const auto ns = static_cast<long long>(n_sets);
  auto vertex_offsets = read_dataset<std::uint32_t>(file, group + "/vertex_offsets", {ns + 1}, "1");
  auto element_offsets = read_dataset<std::uint32_t>(file, group + "/element_offsets", {ns + 1}, "1");
  Dims nv, ne;
  auto points = read_dataset<std::int32_t>(file, group + "/lattice", {-1, 2}, "1", &nv);
  auto elements = read_dataset<std::int32_t>(file, group + "/elements", {-1, 6}, "1", &ne);
  auto first_child = read_dataset<std::int32_t>(file, group + "/first_child", {static_cast<long long>(ne[0])}, "1");
  auto bad = [&](const std::string& what, std::size_t set) {
    return InputError(file.path() + ": '" + group + "' direction set " + std::to_string(set) + ": " + what);
  };
  const std::size_t roots = static_cast<std::size_t>(divisions / 2) * static_cast<std::size_t>(divisions / 2);
  std::vector<model::PanDirections> out(n_sets);
  for (std::size_t s = 0; s < n_sets; ++s) {
    const std::size_t v0 = vertex_offsets[s], v1 = vertex_offsets[s + 1], e0 = element_offsets[s], e1 = element_offsets[s + 1];
    if (v0 > v1 || v1 > nv[0] || e0 > e1 || e1 > ne[0] || (s == 0 && (v0 != 0 || e0 != 0)) ||
        (s + 1 == n_sets && (v1 != nv[0] || e1 != ne[0])))
      throw bad("'vertex_offsets' or 'element_offsets' is not a partition", s);
    if (v1 == v0 && e1 == e0) continue;  // not solved
    if (e1 - e0 < roots) throw bad("fewer elements than the layout's " + std::to_string(roots) + " roots", s);
    auto& set = out[s];
    for (std::size_t v = v0; v < v1; ++v) {
      const std::int32_t a = points[2 * v], b = points[2 * v + 1];
      if (a < 0 || b < 0 || a > lattice - b)
        throw bad("lattice point (" + std::to_string(a) + ", " + std::to_string(b) + ") outside the lattice of " +
                      std::to_string(lattice), s);
      set.vertices.push_back({a, b});
    }
    const std::size_t n_el = e1 - e0, n_vx = v1 - v0;
    for (std::size_t e = 0; e < n_el; ++e) {
      std::array<std::int32_t, 6> nodes{};
      for (std::size_t k = 0; k < 6; ++k) {
        nodes[k] = elements[(e0 + e) * 6 + k];
        if (nodes[k] < 0 || static_cast<std::size_t>(nodes[k]) >= n_vx) throw bad("element node index out of range", s);
      }
      const std::int32_t c = first_child[e0 + e];
      if (c != -1 && (c <= static_cast<std::int64_t>(e) || static_cast<std::size_t>(c) + 4 > n_el))
        throw bad("element " + std::to_string(e) + "'s first child " + std::to_string(c) + " is not after it in the set", s);
      set.elements.push_back(nodes);
      set.first_child.push_back(c);
    }
  }
  return out;
}

// Held-out checks (model::PanHeldOut) as stored: a CSR over the checks of a task or of a bank's
// (proxy, field) pairs, in that order.
void write_held_out(File& file, const std::string& group, const std::vector<const model::PanHeldOut*>& checks) {
  std::vector<std::uint32_t> offsets{0};
  std::vector<float> points, error, raw_l2;  // a check's numbers: float's 7 digits are plenty
  for (const auto* c : checks) {
    if (c->error.size() != c->points_m.size() || c->raw_l2.size() != c->points_m.size())
      throw std::invalid_argument("PAN held-out check: not one error and one L2 per point");
    for (const auto& x : c->points_m) points.insert(points.end(), x.begin(), x.end());
    error.insert(error.end(), c->error.begin(), c->error.end());
    raw_l2.insert(raw_l2.end(), c->raw_l2.begin(), c->raw_l2.end());
    offsets.push_back(static_cast<std::uint32_t>(error.size()));
  }
  create_group(file, group);
  write_dataset<std::uint32_t>(file, group + "/offsets", offsets, {offsets.size()}, "1", true);
  write_dataset<float>(file, group + "/points_m", points, {error.size(), 3}, "m", true);
  write_dataset<float>(file, group + "/error", error, {error.size()}, "1", true);
  write_dataset<float>(file, group + "/raw_l2", raw_l2, {error.size()}, "Pa per unit acceleration", true);
}

std::vector<model::PanHeldOut> read_held_out(const File& file, const std::string& group, std::size_t n_checks) {
  auto offsets = read_dataset<std::uint32_t>(file, group + "/offsets", {static_cast<long long>(n_checks) + 1}, "1");
  Dims n;
  auto error = read_dataset<float>(file, group + "/error", {-1}, "1", &n);
  const auto np = static_cast<long long>(n[0]);
  auto points = read_dataset<float>(file, group + "/points_m", {np, 3}, "m");
  auto raw_l2 = read_dataset<float>(file, group + "/raw_l2", {np}, "Pa per unit acceleration");
  std::vector<model::PanHeldOut> out(n_checks);
  for (std::size_t c = 0; c < n_checks; ++c) {
    if (offsets[c] > offsets[c + 1] || offsets[c + 1] > error.size() || (c == 0 && offsets[0] != 0) ||
        (c + 1 == n_checks && offsets[c + 1] != error.size()))
      throw InputError(file.path() + ": '" + group + "/offsets' is not a partition of the held-out points");
    for (std::uint32_t k = offsets[c]; k < offsets[c + 1]; ++k) {
      out[c].points_m.push_back({points[3 * k], points[3 * k + 1], points[3 * k + 2]});
      out[c].error.push_back(error[k]);
      out[c].raw_l2.push_back(raw_l2[k]);
    }
  }
  return out;
}

// Optional: a bank merged before the checks were made has no /held_out.
void read_held_out(const File& file, PanBank& bank) {
  if (!exists(file, "/held_out")) return;
  auto checks = read_held_out(file, "/held_out", bank.proxies.size() * 6);
  for (std::size_t p = 0; p < bank.proxies.size(); ++p)
    for (std::size_t f = 0; f < 6; ++f) bank.proxies[p].held_out[f] = std::move(checks[p * 6 + f]);
}

// This build writes kPanBankFormatVersion and reads it and 5 (the same values; 6 added mesh entries).
int check_pan_version(const File& file) {
  const auto version = has_attribute(file, "/", "format_version") ? read_attribute<std::int32_t>(file, "/", "format_version") : 0;
  check_header(file, kPanBankFormat, version);  // the format (and a version attribute at all)
  if (version != 5 && version != kPanBankFormatVersion)
    throw InputError(file.path() + ": format '" + kPanBankFormat + "' version " + std::to_string(version) +
                     ", this build reads versions 5 and " + std::to_string(kPanBankFormatVersion));
  return version;
}

void check_lattice(const std::string& path, std::int32_t divisions, std::int32_t max_levels) {
  // DirectionMesh's limits (kernels/pan/direction_mesh.hpp)
  if (divisions < 2 || divisions % 2 != 0 || max_levels < 0 || max_levels > 16 || divisions > (1 << 20) >> max_levels)
    throw InputError(path + ": /bank attributes divisions = " + std::to_string(divisions) + " and max_levels = " +
                     std::to_string(max_levels) + ": need even divisions >= 2 and 0 to 16 levels on a lattice below 2^20");
}

}  // namespace

void write_pan_bank(const std::string& path, const PanBank& bank, const std::string& command,
                    const std::string& config_toml, int n_ranks) {
  const PanBankHeader& h = bank.header;
  if (h.length > 65536) throw std::invalid_argument("PAN bank: wavelet length over 65536 (indices are 16-bit)");
  auto file = File::create(path);
  write_header(file, kPanBankFormat, kPanBankFormatVersion);
  create_group(file, "/bank");
  write_attribute<double>(file, "/bank", "c_m_s", h.c_m_s);
  write_attribute<double>(file, "/bank", "rho_kg_m3", h.rho_kg_m3);
  write_attribute<double>(file, "/bank", "h_s", h.h_s);
  write_attribute<double>(file, "/bank", "dt_s", h.dt_s);
  write_attribute<double>(file, "/bank", "sample_rate_hz", 1.0 / h.dt_s);
  write_attribute<double>(file, "/bank", "t_first_s", h.t_first_s);
  write_attribute(file, "/bank", "time_origin", std::string_view("t = 0 at the centre of psi(t; h); coefficient "
                                                                 "sample n is at retarded time t - R/c = t_first_s + n dt_s"));
  write_attribute<double>(file, "/bank", "epsilon", h.epsilon);
  write_attribute<double>(file, "/bank", "a_m", h.a_m);
  write_attribute(file, "/bank", "radial_model",
                  std::string_view("per coefficient: F (the far field, lim R p), then D_i = R_i p(R_i) - F per radius; "
                                   "R p cubic in 1/R through the four nodes around it, F at 1/R = 0"));
  write_attribute<std::uint32_t>(file, "/bank", "length", h.length);
  write_attribute(file, "/bank", "wavelet", std::string_view("GSL gsl_wavelet_daubechies, member 10 (5 vanishing "
                                                             "moments), periodic, packed ordering"));
  write_attribute<std::int32_t>(file, "/bank", "divisions", h.divisions);
  write_attribute<std::int32_t>(file, "/bank", "max_levels", h.max_levels);
  write_attribute<std::int32_t>(file, "/bank", "lattice", h.lattice());
  write_attribute(file, "/bank", "directions",
                  std::string_view("per (proxy, field) a direction set under /directions: lattice point (a, b) is the "
                                   "direction (a, b, lattice - a - b) / |.| (also in /directions/unit); six-node "
                                   "quadratic elements, the layout's (divisions / 2)^2 roots first, each split into "
                                   "four children where refined (docs/bank-format.md)"));
  write_dataset<double>(file, "/bank/radii_m", h.radii_m, {h.radii_m.size()}, "m");
  std::vector<double> b, c;
  std::vector<const model::PanDirections*> sets;
  for (const auto& p : bank.proxies) {
    b.push_back(p.b_m);
    c.push_back(p.c_m);
    for (int o = 0; o < p.octants(); ++o)
      for (int f = 1; f <= 6; ++f) sets.push_back(&p.field(f, o).directions);
  }
  write_dataset<double>(file, "/proxies/b_m", b, {b.size()}, "m");
  write_dataset<double>(file, "/proxies/c_m", c, {c.size()}, "m");
  std::vector<std::pair<std::uint32_t, const model::PanMeshBody*>> meshes;
  for (std::size_t p = 0; p < bank.proxies.size(); ++p)
    if (bank.proxies[p].is_mesh()) meshes.push_back({static_cast<std::uint32_t>(p), &bank.proxies[p].mesh});
  write_mesh_bodies(file, "/meshes", meshes);
  write_direction_sets(file, "/directions", sets, h.lattice());
  std::vector<const model::PanHeldOut*> checks;
  for (const auto& p : bank.proxies)
    for (const auto& check : p.held_out) checks.push_back(&check);
  write_held_out(file, "/held_out", checks);

  // All coefficients in one compressed CSR, a row per vertex of every set in (proxy, field,
  // vertex) order: a bank is a handful of datasets however many proxies it holds (HDF5 objects
  // cost ~1-2 KB each).
  const std::size_t n_values = h.values();
  const PackedCoefficients packed = pack_coefficients(bank);
  const auto& [offsets, delta, quantized, scale] = packed;
  write_dataset<std::uint32_t>(file, "/coefficients/offsets", offsets, {offsets.size()}, "1", true);
  write_dataset<std::uint16_t>(file, "/coefficients/index_delta", delta, {delta.size()}, "1", true);
  write_dataset<std::int16_t>(file, "/coefficients/values", quantized, {delta.size(), n_values}, "1", true);
  write_dataset<float>(file, "/coefficients/scale", scale, {offsets.size() - 1, n_values}, "Pa m per unit acceleration",
                       true);
  write_sweep_status(file, bank.sweep);
  write_provenance(file, command, config_toml, n_ranks);
  file.commit();
}

void write_pan_task(File& file, const std::string& group, const PanTaskResult& task, std::int32_t lattice,
                    std::size_t n_values) {
  create_group(file, group);
  write_attribute<std::uint32_t>(file, group, "proxy", task.proxy);
  write_attribute<double>(file, group, "b_m", task.b_m);
  write_attribute<double>(file, group, "c_m", task.c_m);
  write_attribute<std::int32_t>(file, group, "field", task.field);
  // A results folder outlives builds: what its values mean is the bank format's (version 5 divided
  // the symmetry zeros out), so a task fitted for another version is refused, not merged.
  write_attribute<std::int32_t>(file, group, "bank_format_version", kPanBankFormatVersion);
  if (!task.mesh.key.empty()) write_mesh_bodies(file, group + "/mesh", {{0u, &task.mesh}});
  std::vector<const model::PanField*> fits{&task.fit};
  for (int o = 1; o < (task.mesh.key.empty() ? 1 : task.mesh.octants); ++o) fits.push_back(&task.other_fits.at(static_cast<std::size_t>(o - 1)));
  std::vector<const model::PanDirections*> sets;
  for (const auto* f : fits) sets.push_back(&f->directions);
  write_direction_sets(file, group + "/directions", sets, lattice);
  std::vector<std::uint32_t> offsets{0}, index;
  std::vector<float> values;
  for (const auto* f : fits)
    for (const auto& d : f->terms) {
      index.insert(index.end(), d.index.begin(), d.index.end());
      values.insert(values.end(), d.value.begin(), d.value.end());
      offsets.push_back(static_cast<std::uint32_t>(index.size()));
    }
  write_dataset<std::uint32_t>(file, group + "/offsets", offsets, {offsets.size()}, "1", true);
  write_dataset<std::uint32_t>(file, group + "/index", index, {index.size()}, "1", true);
  write_dataset<float>(file, group + "/values", values, {index.size(), n_values}, "Pa m per unit acceleration", true);
  const std::size_t n_points = task.held_out_points_m.size();
  if (n_points > 0 && task.held_out_raw.size() % n_points != 0)
    throw std::invalid_argument("PAN task: the held-out series are not one per point");
  std::vector<double> points;
  for (const auto& x : task.held_out_points_m) points.insert(points.end(), x.begin(), x.end());
  write_dataset<double>(file, group + "/held_out_points_m", points, {n_points, 3}, "m", true);
  write_dataset<float>(file, group + "/held_out_raw", task.held_out_raw,
                       {n_points, n_points ? task.held_out_raw.size() / n_points : 0}, "Pa per unit acceleration", true);
}

PanTaskResult read_pan_task(const File& file, const std::string& group, const PanBankHeader& header) {
  PanTaskResult t;
  t.proxy = read_attribute<std::uint32_t>(file, group, "proxy");
  t.b_m = read_attribute<double>(file, group, "b_m");
  t.c_m = read_attribute<double>(file, group, "c_m");
  t.field = read_attribute<std::int32_t>(file, group, "field");
  const auto version = has_attribute(file, group, "bank_format_version")
                           ? read_attribute<std::int32_t>(file, group, "bank_format_version") : 4;
  if (version != kPanBankFormatVersion && version != 5)  // 6 added mesh entries; the values mean the same
    throw InputError(file.path() + ": fitted for PAN bank format version " + std::to_string(version) +
                     ", this build writes version " + std::to_string(kPanBankFormatVersion) +
                     ": rerun its task (delete the file, or start the sweep without --resume)");
  read_mesh_bodies(file, group + "/mesh", {&t.mesh});
  const int n_octants = t.mesh.key.empty() ? 1 : t.mesh.octants;
  std::vector<model::PanField*> fits{&t.fit};
  for (int o = 1; o < n_octants; ++o) fits.push_back(&t.other_fits.at(static_cast<std::size_t>(o - 1)));
  auto sets = read_direction_sets(file, group + "/directions", fits.size(), header.divisions, header.lattice());
  std::size_t n_directions = 0;
  for (std::size_t o = 0; o < fits.size(); ++o) {
    if (sets[o].vertices.empty()) throw InputError(file.path() + ": '" + group + "/directions' holds no direction");
    n_directions += sets[o].vertices.size();
    fits[o]->directions = std::move(sets[o]);
  }
  const std::size_t n_values = header.values();
  auto offsets = read_dataset<std::uint32_t>(file, group + "/offsets", {static_cast<long long>(n_directions) + 1}, "1");
  Dims n;
  auto index = read_dataset<std::uint32_t>(file, group + "/index", {-1}, "1", &n);
  auto values = read_dataset<float>(file, group + "/values", {static_cast<long long>(n[0]), static_cast<long long>(n_values)},
                                    "Pa m per unit acceleration");
  std::size_t d = 0;
  for (auto* fit : fits)
    for (std::size_t v = 0; v < fit->directions.vertices.size(); ++v, ++d) {
      if (offsets[d] > offsets[d + 1] || offsets[d + 1] > index.size())
        throw InputError(file.path() + ": '" + group + "/offsets' is not a partition of the coefficients");
      SparseTerms terms_d;
      for (std::uint32_t e = offsets[d]; e < offsets[d + 1]; ++e) {
        if (index[e] >= header.length || (e > offsets[d] && index[e] <= index[e - 1]))
          throw InputError(file.path() + ": '" + group + "/index' is out of range or not ascending");
        terms_d.index.push_back(index[e]);
        for (std::size_t k = 0; k < n_values; ++k) terms_d.value.push_back(values[e * n_values + k]);
      }
      fit->terms.push_back(std::move(terms_d));
    }
  Dims np;
  auto points = read_dataset<double>(file, group + "/held_out_points_m", {-1, 3}, "m", &np);
  for (std::size_t k = 0; k < np[0]; ++k) t.held_out_points_m.push_back({points[3 * k], points[3 * k + 1], points[3 * k + 2]});
  t.held_out_raw = read_dataset<float>(file, group + "/held_out_raw", {static_cast<long long>(np[0]), -1},
                                       "Pa per unit acceleration");
  return t;
}

PanBank read_pan_bank(const std::string& path) {
  auto file = File::open(path);
  check_pan_version(file);
  PanBank bank;
  PanBankHeader& h = bank.header;
  h.c_m_s = read_attribute<double>(file, "/bank", "c_m_s");
  h.rho_kg_m3 = read_attribute<double>(file, "/bank", "rho_kg_m3");
  h.h_s = read_attribute<double>(file, "/bank", "h_s");
  h.dt_s = read_attribute<double>(file, "/bank", "dt_s");
  h.t_first_s = read_attribute<double>(file, "/bank", "t_first_s");
  h.epsilon = read_attribute<double>(file, "/bank", "epsilon");
  h.a_m = read_attribute<double>(file, "/bank", "a_m");
  h.length = read_attribute<std::uint32_t>(file, "/bank", "length");
  if (h.length < 2 || (h.length & (h.length - 1)) != 0 || !(h.dt_s > 0))
    throw InputError(path + ": /bank attributes length or dt_s out of range");
  h.divisions = read_attribute<std::int32_t>(file, "/bank", "divisions");
  h.max_levels = read_attribute<std::int32_t>(file, "/bank", "max_levels");
  check_lattice(path, h.divisions, h.max_levels);
  h.radii_m = read_dataset<double>(file, "/bank/radii_m", {-1}, "m");
  for (std::size_t i = 0; i < h.radii_m.size(); ++i)  // the radial model's nodes (kernels/pan/radial.hpp)
    if (!(h.radii_m[i] > 0 && std::isfinite(h.radii_m[i])) || (i > 0 && !(h.radii_m[i] > h.radii_m[i - 1])))
      throw InputError(path + ": '/bank/radii_m' must be positive, finite and ascending (entry " + std::to_string(i) +
                       " is " + std::to_string(h.radii_m[i]) + ")");
  Dims nb;
  auto b = read_dataset<double>(file, "/proxies/b_m", {-1}, "m", &nb);
  auto c = read_dataset<double>(file, "/proxies/c_m", {static_cast<long long>(nb[0])}, "m");
  const std::size_t n_values = h.values(), np = b.size();
  bank.proxies.resize(np);
  std::vector<model::PanMeshBody*> bodies;
  for (auto& p : bank.proxies) bodies.push_back(&p.mesh);
  read_mesh_bodies(file, "/meshes", bodies);
  std::size_t n_sets = 0;
  for (const auto& p : bank.proxies) n_sets += 6 * static_cast<std::size_t>(p.octants());
  auto sets = read_direction_sets(file, "/directions", n_sets, h.divisions, h.lattice());
  std::size_t rows = 0;
  for (const auto& s : sets) rows += s.vertices.size();
  const auto nv = static_cast<long long>(n_values), nr = static_cast<long long>(rows);
  auto offsets = read_dataset<std::uint32_t>(file, "/coefficients/offsets", {nr + 1}, "1");
  Dims nnz;
  auto delta = read_dataset<std::uint16_t>(file, "/coefficients/index_delta", {-1}, "1", &nnz);
  auto values = read_dataset<std::int16_t>(file, "/coefficients/values", {static_cast<long long>(nnz[0]), nv}, "1");
  auto scale = read_dataset<float>(file, "/coefficients/scale", {nr, nv}, "Pa m per unit acceleration");
  const PackedCoefficients packed{std::move(offsets), std::move(delta), std::move(values), std::move(scale)};
  std::size_t row = 0, set = 0;
  for (std::size_t p = 0; p < np; ++p) {
    PanProxy& proxy = bank.proxies[p];
    proxy.b_m = b[p];
    proxy.c_m = c[p];
    for (int o = 0; o < proxy.octants(); ++o)
      for (int f = 1; f <= 6; ++f, ++set) {
        model::PanField& field = proxy.field(f, o);
        field.directions = std::move(sets[set]);
        unpack_field(h, packed, row, field,
                     path + ": '/directions' set " + std::to_string(set) + " (proxy " + std::to_string(p) + ", field " +
                         std::to_string(f) + (proxy.octants() > 1 ? ", octant " + std::to_string(o) : std::string()) + ")");
      }
  }
  read_held_out(file, bank);
  bank.sweep = read_sweep_status(file);
  return bank;
}

model::PanField stored_field(const PanBankHeader& header, const model::PanField& field) {
  PanBank one;
  one.header = header;
  one.proxies.resize(1);
  one.proxies[0].fields[0] = field;
  const PackedCoefficients packed = pack_coefficients(one);
  model::PanField out;
  out.directions = field.directions;
  std::size_t row = 0;
  unpack_field(header, packed, row, out, "stored_field");
  return out;
}

}  // namespace clatter::io
