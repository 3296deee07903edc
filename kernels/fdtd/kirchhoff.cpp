#include "kernels/fdtd/kirchhoff.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/stage_log.hpp"

namespace clatter::kernels::fdtd {

namespace {

constexpr int kLayers = 4;  // cells across a face: -2, -1 inside, 0, +1 outside
// Fourth-order weights of those cells for the face value and the normal derivative (times dx).
constexpr std::array<double, kLayers> kValueWeight{-1.0 / 16, 9.0 / 16, 9.0 / 16, -1.0 / 16};
constexpr std::array<double, kLayers> kSlopeWeight{1.0 / 24, -27.0 / 24, 27.0 / 24, -1.0 / 24};

// Global index of the cell whose centre has coordinate x_m along `axis`.
int cell_index(const Grid& grid, int axis, double x_m) {
  return static_cast<int>(std::lround(x_m / grid.dx_m - 0.5)) + grid.origin(axis);
}

// The cells across element e, innermost first, each with the sign its value takes: in octant mode
// a cell past a mirror plane (near the surface's rim, the inner cells of a face can be) is read as its
// image in the octant, times the field's parity (eqs. 16-21).
struct AcrossCells {
  std::array<std::array<int, 3>, kLayers> cell{};
  std::array<double, kLayers> sign{};
};
AcrossCells element_cells(const Grid& grid, const SurfaceElement& e, int field) {
  AcrossCells out;
  for (int l = 0; l < kLayers; ++l) {
    std::array<double, 3> c = e.centre_m;
    c[e.axis] += e.sign * (l - 1.5) * grid.dx_m;
    out.sign[l] = 1;
    for (int a = 0; a < 3; ++a) {
      int i = cell_index(grid, a, c[a]);
      if (grid.octant && i < 0) {
        i = -i - 1;
        out.sign[l] *= field_parity(field, a);
      }
      out.cell[l][a] = i;
    }
  }
  return out;
}

// p and dp/dn at a face from its four cells (with their image signs), in one fixed order: the same
// bits whether the cells' owner combines them or rank 0 does after the gather.
std::pair<float, float> face_values(const std::array<float, kLayers>& v, const std::array<double, kLayers>& sign, double dx_m) {
  double value = 0, slope = 0;
  for (std::size_t l = 0; l < kLayers; ++l) {
    value += sign[l] * kValueWeight[l] * v[l];
    slope += sign[l] * kSlopeWeight[l] * v[l];
  }
  return {static_cast<float>(value), static_cast<float>(slope / dx_m)};
}

// One element-image's copy into the accumulators: a0 += fp p + fn n, a1 += ft p over [k0, k1).
// Nearly all of a PAN task's time (docs/benchmarks.md, BM_KirchhoffPoint). Cloned for AVX-512 and
// AVX2: the rows are the element's contiguous series, so the wide loads do not split the way the
// FDTD's 260-float rows do. Each sample's arithmetic is the same in every clone (no FMA
// contraction, -ffp-contract=off), so the bits do not depend on the CPU.
__attribute__((target_clones("avx512f", "avx2", "default")))
void accumulate_row(float* __restrict a0, float* __restrict a1, const float* __restrict ps, const float* __restrict ns,
                    float fp, float fn, float ft, long k0, long k1) {
  for (long k = k0; k < k1; ++k) {
    a0[k] += fp * ps[k] + fn * ns[k];
    a1[k] += ft * ps[k];
  }
}

// Sums of weighted, delayed copies of the surface series, in two sets (the second is
// differentiated in time at the end). A copy delayed by a fractional number of samples is added
// at its whole-sample shift into one of kBins accumulators by its fraction, and each accumulator
// is interpolated once at the end (Lagrange, six samples): one add per element and sample instead
// of six. The fraction is rounded to 1/kBins of a sample, a phase error of at most pi f dt / kBins.
// Measured on a monopole of psi(t; 1e-4 s) at 96 kHz through a surface at 6.5 mm (Kirchhoff test):
// 32 bins left 0.18 % and stopped the error from falling as dx^2; 128 bins leave the quadrature's
// 0.09 %, which falls to 0.023 % at half the cell and step. The accumulators are float (the series
// are): half the memory traffic and twice the SIMD width, 1.9x faster per point at the paper's
// resolution, and the tests read the same to three digits as with double.
class DelaySum {
 public:
  static constexpr int kBins = 128, kTapsBefore = 2, kTapsAfter = 3;
  // The Lagrange weights of samples -kTapsBefore .. kTapsAfter at the fraction f in [0, 1).
  static std::array<double, kTapsBefore + kTapsAfter + 1> lagrange_weights(double f) {
    std::array<double, kTapsBefore + kTapsAfter + 1> w{};
    for (int i = -kTapsBefore; i <= kTapsAfter; ++i) {
      double v = 1;
      for (int j = -kTapsBefore; j <= kTapsAfter; ++j)
        if (j != i) v *= (f - j) / (i - j);
      w[static_cast<std::size_t>(i + kTapsBefore)] = v;
    }
    return w;
  }
  // Output sample k reads input sample k + delay - lead: the output starts `lead` samples earlier.
  DelaySum(int n_in, int lead)
      : n_in_(n_in), lead_(lead), n_(n_in + lead), acc_(2, std::vector<float>(kBins * static_cast<std::size_t>(n_), 0.0f)) {}
  // The accumulators' size.
  static std::size_t bytes(int n_in, int lead) { return 2 * kBins * static_cast<std::size_t>(n_in + lead) * sizeof(float); }

  // Adds (wp p + wn n)[k + delay - lead] to set 0 and wt p[k + delay - lead] to set 1 for every
  // output sample k: one pass over an element's two series. (Summing the copies a tile of 256
  // output samples at a time, so the accumulators stay in L2, was 2.9x slower: each tile then
  // reads every element's series again, and those reads, not the accumulators, are what wait.)
  void add(double delay_samples, double wp, double wn, double wt, const float* p, const float* n) {
    const double whole = std::floor(delay_samples);
    long shift = static_cast<long>(whole) - lead_;
    int bin = static_cast<int>(std::lround((delay_samples - whole) * kBins));
    if (bin == kBins) {
      bin = 0;
      ++shift;
    }
    max_shift_ = std::max(max_shift_, shift);
    const std::size_t row = static_cast<std::size_t>(bin) * static_cast<std::size_t>(n_);
    const long k0 = std::max(0L, -shift), k1 = std::min<long>(n_, n_in_ - shift);
    accumulate_row(acc_[0].data() + row, acc_[1].data() + row, p + shift, n + shift, static_cast<float>(wp),
                   static_cast<float>(wn), static_cast<float>(wt), k0, k1);
  }

  // scale x (set 0 + d/dt set 1), with the samples that needed data past the record's end zeroed.
  KirchhoffSeries result(double scale, double t_first_s, double dt_s) const {
    std::array<std::vector<double>, 2> sets;
    for (int s = 0; s < 2; ++s) {
      sets[static_cast<std::size_t>(s)].assign(static_cast<std::size_t>(n_), 0.0);
      for (int b = 0; b < kBins; ++b) {
        const auto w = lagrange_weights(static_cast<double>(b) / kBins);
        const float* a = acc_[static_cast<std::size_t>(s)].data() + static_cast<std::size_t>(b) * static_cast<std::size_t>(n_);
        auto& out = sets[static_cast<std::size_t>(s)];
        for (int k = 0; k < n_; ++k)
          for (int t = -kTapsBefore; t <= kTapsAfter; ++t)
            if (k + t >= 0 && k + t < n_)
              out[static_cast<std::size_t>(k)] += w[static_cast<std::size_t>(t + kTapsBefore)] * a[k + t];
      }
    }
    KirchhoffSeries r;
    r.value.assign(static_cast<std::size_t>(n_), 0.0);
    // Sample k read the series up to k + max_shift + kTapsAfter, and the derivative reads k + 2.
    r.valid_end = static_cast<int>(std::clamp<long>(std::min<long>(n_ - 2, n_in_ - 1 - kTapsAfter - max_shift_) - 2, 0, n_));
    r.t_first_s = t_first_s - lead_ * dt_s;
    const auto& a = sets[0];
    const auto& b = sets[1];
    auto at = [&](int k) { return k >= 0 && k < n_ ? b[static_cast<std::size_t>(k)] : 0.0; };
    for (int k = 0; k < r.valid_end; ++k) {
      const double db = (at(k - 2) - 8 * at(k - 1) + 8 * at(k + 1) - at(k + 2)) / (12 * dt_s);
      r.value[static_cast<std::size_t>(k)] = scale * (a[static_cast<std::size_t>(k)] + db);
    }
    return r;
  }

 private:
  int n_in_, lead_, n_;
  long max_shift_ = -(1L << 40);
  std::vector<std::vector<float>> acc_;  // [set][bin][sample]
};

// The images of the surface's elements: identity, or in octant mode the 8 mirrors (bit a of m flips
// axis a) with the field's parity.
struct Image {
  std::array<int, 3> flip{};
  double sign = 1;
};
std::vector<Image> images(const SurfaceField& s) {
  std::vector<Image> out;
  for (int m = 0; m < (s.octant ? 8 : 1); ++m) {
    Image im;
    for (int a = 0; a < 3; ++a) {
      im.flip[a] = (m >> a) & 1 ? -1 : 1;
      if (im.flip[a] < 0) im.sign *= field_parity(s.field, a);
    }
    out.push_back(im);
  }
  return out;
}

}  // namespace

std::vector<SurfaceElement> staircase_surface(const Grid& grid, const SurfaceShape& shape) {
  const double dx = grid.dx_m, radius_m = shape.radius_m;
  const auto& box = shape.half_box_m;
  auto inside = [&](const std::array<double, 3>& c) {
    return c[0] * c[0] + c[1] * c[1] + c[2] * c[2] <= radius_m * radius_m && std::abs(c[0]) <= box[0] &&
           std::abs(c[1]) <= box[1] && std::abs(c[2]) <= box[2];
  };
  const int m = static_cast<int>(std::ceil(radius_m / dx)) + 1;  // cells per half axis that can be inside
  const int lo = grid.octant ? 0 : -m;
  std::vector<SurfaceElement> out;
  // Cell (i, j, k) has its centre at ((i, j, k) + 1/2) dx from the origin; a face is an element
  // where the cell is inside and its neighbour across it is not (in octant mode the neighbour
  // across a mirror plane is the cell's own image, inside with it).
  for (int i = lo; i < m; ++i)
    for (int j = lo; j < m; ++j)
      for (int k = lo; k < m; ++k) {
        const std::array<double, 3> c{(i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx};
        if (!inside(c)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int sign : {-1, 1}) {
            std::array<double, 3> n = c;
            n[axis] += sign * dx;
            if (inside(n)) continue;
            SurfaceElement e;
            e.axis = axis;
            e.sign = sign;
            e.centre_m = c;
            e.centre_m[axis] += sign * 0.5 * dx;
            out.push_back(e);
          }
      }
  const Box interior = grid.interior();
  for (const auto& e : out)
    for (const auto& c : element_cells(grid, e, 0).cell)
      if (!interior.contains(c))
        throw std::invalid_argument("Kirchhoff surface: radius " + std::to_string(radius_m) +
                                    " m reaches past the grid's interior (the absorbing layer or the edge)");
  return out;
}

double outside_radius_m(const std::vector<SurfaceElement>& elements, double dx_m) {
  double r = 0;
  for (const auto& e : elements) r = std::max(r, std::hypot(e.centre_m[0], e.centre_m[1], e.centre_m[2]));
  return r + dx_m;  // a face's corners lie within dx / sqrt(2) of its centre
}

SurfaceRecorder::SurfaceRecorder(const Problem& problem, const SurfaceShape& shape, const Layout& layout, int n_samples)
    : n_samples_(static_cast<std::size_t>(n_samples)), dx_m_(problem.grid.dx_m) {
  const auto elements = staircase_surface(problem.grid, shape);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto across = element_cells(problem.grid, elements[e], problem.field);
    bool all = true;
    for (const auto& c : across.cell) all = all && layout.owned.contains(c);
    if (all) {
      Whole w{static_cast<int>(e), {}, across.sign};
      for (int l = 0; l < kLayers; ++l) w.index[static_cast<std::size_t>(l)] = layout.at(across.cell[static_cast<std::size_t>(l)]);
      whole_.push_back(w);
      continue;
    }
    for (int l = 0; l < kLayers; ++l)
      if (layout.owned.contains(across.cell[static_cast<std::size_t>(l)]))
        cells_.push_back({static_cast<int>(e) * kLayers + l, layout.at(across.cell[static_cast<std::size_t>(l)])});
  }
  whole_series_.resize(whole_.size() * 2 * n_samples_);
  cell_series_.resize(cells_.size() * n_samples_);
}

void SurfaceRecorder::record(int n, const float* pressure) {
  Stage s("record");
  const auto k = static_cast<std::size_t>(n);
  for (std::size_t q = 0; q < whole_.size(); ++q) {
    std::array<float, kLayers> v{};
    for (std::size_t l = 0; l < kLayers; ++l) v[l] = pressure[static_cast<std::size_t>(whole_[q].index[l])];
    const auto [p, dpdn] = face_values(v, whole_[q].sign, dx_m_);
    whole_series_[(2 * q) * n_samples_ + k] = p;
    whole_series_[(2 * q + 1) * n_samples_ + k] = dpdn;
  }
  for (std::size_t q = 0; q < cells_.size(); ++q)
    cell_series_[q * n_samples_ + k] = pressure[static_cast<std::size_t>(cells_[q].index)];
}

bool SurfaceRecorder::finite_at(int n) const {
  bool finite = true;
  for (std::size_t q = static_cast<std::size_t>(n); q < whole_series_.size(); q += n_samples_)
    if (!std::isfinite(whole_series_[q])) finite = false;
  for (std::size_t q = static_cast<std::size_t>(n); q < cell_series_.size(); q += n_samples_)
    if (!std::isfinite(cell_series_[q])) finite = false;
  return finite;
}

std::string SurfaceRecorder::pack() const {
  std::string out;
  out.reserve(whole_.size() * (sizeof(int) + 2 * sizeof(float) * n_samples_) +
              cells_.size() * (sizeof(int) + sizeof(float) * n_samples_));
  for (std::size_t q = 0; q < whole_.size(); ++q) {
    const int id = -(whole_[q].element + 1);
    out.append(reinterpret_cast<const char*>(&id), sizeof(int));
    out.append(reinterpret_cast<const char*>(&whole_series_[2 * q * n_samples_]), 2 * sizeof(float) * n_samples_);
  }
  for (std::size_t q = 0; q < cells_.size(); ++q) {
    out.append(reinterpret_cast<const char*>(&cells_[q].id), sizeof(int));
    out.append(reinterpret_cast<const char*>(&cell_series_[q * n_samples_]), sizeof(float) * n_samples_);
  }
  return out;
}

SurfaceField empty_surface(const Problem& problem, const SurfaceShape& shape, int n_samples, double t_first_s) {
  SurfaceField s;
  s.elements = staircase_surface(problem.grid, shape);
  s.n_samples = n_samples;
  s.dx_m = problem.grid.dx_m;
  s.dt_s = problem.dt_s;
  s.c_m_s = problem.c_m_s;
  s.t_first_s = t_first_s;
  s.octant = problem.grid.octant;
  s.field = problem.field;
  s.p.assign(s.elements.size() * static_cast<std::size_t>(n_samples), 0.0f);
  s.dpdn.assign(s.p.size(), 0.0f);
  return s;
}

SurfaceField assemble_surface(const Problem& problem, const SurfaceShape& shape, int n_samples, double t_first_s,
                              const std::vector<std::string>& packs) {
  SurfaceField s = empty_surface(problem, shape, n_samples, t_first_s);
  const std::size_t ns = static_cast<std::size_t>(n_samples), ne = s.elements.size();
  std::vector<char> done(ne, 0);
  // Single cells, by id: combined below in a fixed order, whatever the split.
  std::vector<const char*> where(ne * kLayers, nullptr);
  for (const auto& text : packs)
    for (std::size_t off = 0; off + sizeof(int) <= text.size();) {
      int id = 0;
      std::memcpy(&id, text.data() + off, sizeof id);
      off += sizeof id;
      if (id < 0) {  // a whole element: p, then dp/dn
        const auto e = static_cast<std::size_t>(-id - 1);
        if (e >= ne || done[e] || off + 2 * ns * sizeof(float) > text.size())
          throw std::logic_error("assemble_surface: an element out of range or recorded twice");
        std::memcpy(&s.p[e * ns], text.data() + off, ns * sizeof(float));
        std::memcpy(&s.dpdn[e * ns], text.data() + off + ns * sizeof(float), ns * sizeof(float));
        done[e] = 1;
        off += 2 * ns * sizeof(float);
        continue;
      }
      if (static_cast<std::size_t>(id) >= where.size() || where[static_cast<std::size_t>(id)] ||
          off + ns * sizeof(float) > text.size())
        throw std::logic_error("assemble_surface: a cell id out of range or recorded twice");
      where[static_cast<std::size_t>(id)] = text.data() + off;
      off += ns * sizeof(float);
    }
  std::array<std::vector<float>, kLayers> cell;
  for (auto& c : cell) c.resize(ns);
  for (std::size_t e = 0; e < ne; ++e) {
    if (done[e]) continue;
    const auto across = element_cells(problem.grid, s.elements[e], problem.field);
    for (std::size_t l = 0; l < kLayers; ++l) {
      const char* src = where[e * kLayers + l];
      if (!src) throw std::logic_error("assemble_surface: a cell of the surface was recorded by no block");
      std::memcpy(cell[l].data(), src, ns * sizeof(float));
    }
    for (std::size_t k = 0; k < ns; ++k) {
      const auto [p, dpdn] = face_values({cell[0][k], cell[1][k], cell[2][k], cell[3][k]}, across.sign, s.dx_m);
      s.p[e * ns + k] = p;
      s.dpdn[e * ns + k] = dpdn;
    }
  }
  return s;
}

namespace {

// Listeners 0 .. count - 1 heard through the surface in groups whose sums together stay within
// kGroupBytes, each group in one pass: element after element, each listener's copies of it in
// turn (copy(q, element, image, sum)). An element's series is then read from memory once per
// group, and each listener's sum still sees its copies in the order it would alone: the same
// bits. BM_KirchhoffPoints, one core: a full-domain surface's points (one image) wait on the
// series, 1.47e9 element-samples/s alone, 2.50e9 in threes, 2.86e9 in fives, 2.1e9 in nines (the
// sums past the caches); an octant surface's (8 images, the series already reused) 3.83e9 alone,
// 4.05e9 in threes, 2.87e9 in nines. Threes also held 2.46-2.67e9 with both cores at it.
template <class Copy>
std::vector<KirchhoffSeries> hear_in_groups(const SurfaceField& s, std::size_t count, int lead, Copy copy) {
  constexpr std::size_t kGroupBytes = 8u << 20;
  const std::size_t group = std::max<std::size_t>(1, kGroupBytes / std::max<std::size_t>(1, DelaySum::bytes(s.n_samples, lead)));
  const auto mirrors = images(s);
  std::vector<KirchhoffSeries> out;
  out.reserve(count);
  for (std::size_t first = 0; first < count; first += group) {
    const std::size_t last = std::min(count, first + group);
    std::vector<DelaySum> sums;
    sums.reserve(last - first);
    for (std::size_t q = first; q < last; ++q) sums.emplace_back(s.n_samples, lead);
    for (std::size_t e = 0; e < s.elements.size(); ++e)
      for (const auto& im : mirrors)
        for (std::size_t q = first; q < last; ++q) copy(q, e, im, sums[q - first]);
    for (const auto& sum : sums) out.push_back(sum.result(s.dx_m * s.dx_m / (4 * std::numbers::pi), s.t_first_s, s.dt_s));
  }
  return out;
}

}  // namespace

std::vector<KirchhoffSeries> far_field(const SurfaceField& s, const std::vector<FarListener>& listeners) {
  Stage stage("far field");
  std::vector<std::array<double, 3>> u;
  for (const auto& l : listeners) {
    const auto& d = l.direction;
    const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(norm > 0)) throw std::invalid_argument("far_field: the direction is zero");
    u.push_back({d[0] / norm, d[1] / norm, d[2] / norm});
  }
  // Elements on the near side reach a far listener up to the surface's radius / c before its
  // centre does: the far field starts that much before the record.
  double reach_m = 0;
  for (const auto& el : s.elements) reach_m = std::max(reach_m, std::hypot(el.centre_m[0], el.centre_m[1], el.centre_m[2]));
  const int lead = static_cast<int>(std::ceil(reach_m / (s.c_m_s * s.dt_s))) + DelaySum::kTapsAfter + 1;
  const std::size_t ns = static_cast<std::size_t>(s.n_samples);
  return hear_in_groups(s, listeners.size(), lead, [&](std::size_t q, std::size_t e, const Image& im, DelaySum& sum) {
    const auto& el = s.elements[e];
    double dy = 0;
    for (int a = 0; a < 3; ++a) dy += u[q][a] * im.flip[a] * el.centre_m[a];
    const double nd = el.sign * im.flip[el.axis] * u[q][el.axis];
    const double delay = dy / (s.c_m_s * s.dt_s) + listeners[q].advance_s / s.dt_s;
    // (F): the dp/dt term goes to the differentiated set.
    sum.add(delay, 0.0, -im.sign, im.sign * nd / s.c_m_s, &s.p[e * ns], &s.dpdn[e * ns]);
  });
}

KirchhoffSeries far_field(const SurfaceField& s, const std::array<double, 3>& d, double advance_s) {
  return std::move(far_field(s, std::vector<FarListener>{{d, advance_s}}).front());
}

std::vector<KirchhoffSeries> pressure_at(const SurfaceField& s, const std::vector<std::array<double, 3>>& x_m,
                                         double advance_s) {
  Stage stage("Kirchhoff point");
  const double outside_m = outside_radius_m(s.elements, s.dx_m);
  for (const auto& x : x_m)
    if (std::hypot(x[0], x[1], x[2]) <= outside_m)
      throw std::invalid_argument("pressure_at: the point is not outside the Kirchhoff surface");
  const std::size_t ns = static_cast<std::size_t>(s.n_samples);
  return hear_in_groups(s, x_m.size(), 0, [&](std::size_t q, std::size_t e, const Image& im, DelaySum& sum) {
    const auto& el = s.elements[e];
    std::array<double, 3> rv{};
    double r2 = 0;
    for (int a = 0; a < 3; ++a) {
      rv[a] = x_m[q][a] - im.flip[a] * el.centre_m[a];
      r2 += rv[a] * rv[a];
    }
    const double r = std::sqrt(r2);
    const double nr = el.sign * im.flip[el.axis] * rv[el.axis] / r;
    const double delay = (advance_s - r / s.c_m_s) / s.dt_s;
    sum.add(delay, im.sign * nr / r2, -im.sign / r, im.sign * nr / (s.c_m_s * r), &s.p[e * ns], &s.dpdn[e * ns]);
  });
}

KirchhoffSeries pressure_at(const SurfaceField& s, const std::array<double, 3>& x_m, double advance_s) {
  return std::move(pressure_at(s, std::vector<std::array<double, 3>>{x_m}, advance_s).front());
}

}  // namespace clatter::kernels::fdtd
