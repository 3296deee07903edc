#include "kernels/transfer/mesh_transfer.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "kernels/transfer/equivalent_sources.hpp"
#include "kernels/transfer/special_functions.hpp"
#include "kernels/transfer/surface_interpolation.hpp"

namespace clatter::kernels::transfer {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::complex<double> kI(0, 1);

// ---- the curved 6-node face -------------------------------------------------------------------

// Quadratic shape functions at parameters (s, t) of the face (corner 0 at (0,0), 1 at (1,0),
// 2 at (0,1); mid-nodes of 01, 12, 20) and their derivatives.
struct ShapeValues {
  std::array<double, 6> n, ds, dt;
};
ShapeValues shape_values(double s, double t) {
  const double l = 1 - s - t;
  return {{l * (2 * l - 1), s * (2 * s - 1), t * (2 * t - 1), 4 * l * s, 4 * s * t, 4 * t * l},
          {1 - 4 * l, 4 * s - 1, 0, 4 * (l - s), 4 * t, -4 * t},
          {1 - 4 * l, 0, 4 * t - 1, -4 * s, 4 * s, 4 * (l - t)}};
}

Eigen::Vector3d node(std::span<const std::array<double, 3>> nodes, std::int32_t i) {
  const auto& p = nodes[static_cast<std::size_t>(i)];
  return {p[0], p[1], p[2]};
}

enum class Rule { kCentroid, kThreePoint, kOffCentre };

// Every face split n x n in its parameters (n from the longest corner edge over spacing_m), a
// rule on each part; weights are areas of the curved face.
MeshSurfacePoints sample_surface(std::span<const std::array<double, 3>> nodes,
                                 std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shape,
                                 double spacing_m, Rule rule) {
  MeshSurfacePoints out;
  std::vector<std::array<double, 3>> local;  // barycentric (s, t) and weight on the unit parameter triangle
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    std::array<Eigen::Vector3d, 6> x;
    for (std::size_t a = 0; a < 6; ++a) x[a] = node(nodes, face[a]);
    const double edge = std::max({(x[0] - x[1]).norm(), (x[1] - x[2]).norm(), (x[2] - x[0]).norm()});
    const int n = std::max(1, static_cast<int>(std::ceil(edge / spacing_m)));
    local.clear();
    const double area = 0.5 / (n * n);
    auto add_part = [&](const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& p2) {
      switch (rule) {
        case Rule::kCentroid: {
          const Eigen::Vector2d c = (p0 + p1 + p2) / 3;
          local.push_back({c.x(), c.y(), area});
          break;
        }
        case Rule::kThreePoint:
          for (int k = 0; k < 3; ++k) {
            const Eigen::Vector2d& a = k == 0 ? p0 : (k == 1 ? p1 : p2);
            const Eigen::Vector2d& b = k == 0 ? p1 : (k == 1 ? p2 : p0);
            const Eigen::Vector2d& c = k == 0 ? p2 : (k == 1 ? p0 : p1);
            const Eigen::Vector2d q = (4 * a + b + c) / 6;
            local.push_back({q.x(), q.y(), area / 3});
          }
          break;
        case Rule::kOffCentre: {  // first order, but at points no centroid rule uses
          const Eigen::Vector2d q = (4 * p0 + p1 + p2) / 6;
          local.push_back({q.x(), q.y(), area});
          break;
        }
      }
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const Eigen::Vector2d a(double(i) / n, double(j) / n), b(double(i + 1) / n, double(j) / n),
            c(double(i) / n, double(j + 1) / n), d(double(i + 1) / n, double(j + 1) / n);
        add_part(a, b, c);
        if (i + j < n - 1) add_part(b, d, c);
      }
    for (const auto& [s, t, w] : local) {
      const ShapeValues v = shape_values(s, t);
      Eigen::Vector3d p = Eigen::Vector3d::Zero(), ts = p, tt = p, u = p;
      for (std::size_t a = 0; a < 6; ++a) {
        p += v.n[a] * x[a];
        ts += v.ds[a] * x[a];
        tt += v.dt[a] * x[a];
        if (!shape.empty()) {
          const std::size_t at = 3 * static_cast<std::size_t>(face[a]);
          u += v.n[a] * Eigen::Vector3d(shape[at], shape[at + 1], shape[at + 2]);
        }
      }
      const Eigen::Vector3d cross = ts.cross(tt);
      const double jacobian = cross.norm();
      if (jacobian == 0) continue;
      out.position_m.push_back(p);
      out.normal.push_back(cross / jacobian);
      out.weight_m2.push_back(w * jacobian);
      out.displacement_m.push_back(u);
    }
  }
  return out;
}

// ---- spatial searches ---------------------------------------------------------------------------

// A static kd-tree over points: is any point nearer than r to y.
class KdTree {
 public:
  explicit KdTree(const std::vector<Eigen::Vector3d>& points) : points_(points), index_(points.size()) {
    std::iota(index_.begin(), index_.end(), 0);
    build(0, index_.size(), 0);
  }
  bool any_within(const Eigen::Vector3d& y, double r) const { return search(0, index_.size(), 0, y, r * r); }

 private:
  void build(std::size_t lo, std::size_t hi, int axis) {
    if (hi - lo <= 8) return;
    const std::size_t mid = (lo + hi) / 2;
    std::nth_element(index_.begin() + static_cast<std::ptrdiff_t>(lo), index_.begin() + static_cast<std::ptrdiff_t>(mid),
                     index_.begin() + static_cast<std::ptrdiff_t>(hi),
                     [&](std::size_t a, std::size_t b) { return points_[a](axis) < points_[b](axis); });
    build(lo, mid, (axis + 1) % 3);
    build(mid + 1, hi, (axis + 1) % 3);
  }
  bool search(std::size_t lo, std::size_t hi, int axis, const Eigen::Vector3d& y, double r2) const {
    if (hi - lo <= 8) {
      for (std::size_t i = lo; i < hi; ++i)
        if ((points_[index_[i]] - y).squaredNorm() < r2) return true;
      return false;
    }
    const std::size_t mid = (lo + hi) / 2;
    const Eigen::Vector3d& p = points_[index_[mid]];
    if ((p - y).squaredNorm() < r2) return true;
    const double d = y(axis) - p(axis);
    const int next = (axis + 1) % 3;
    if (d < 0) {
      if (search(lo, mid, next, y, r2)) return true;
      return d * d < r2 && search(mid + 1, hi, next, y, r2);
    }
    if (search(mid + 1, hi, next, y, r2)) return true;
    return d * d < r2 && search(lo, mid, next, y, r2);
  }
  const std::vector<Eigen::Vector3d>& points_;
  std::vector<std::size_t> index_;
};

// Points hashed into cubes of a fixed size, for neighbour queries within about that size.
class HashGrid {
 public:
  explicit HashGrid(double cell_m) : cell_(cell_m) {}
  void insert(const Eigen::Vector3d& x, std::size_t id) { cells_[key(cell_of(x))].push_back(id); }
  template <class F>
  void for_near(const Eigen::Vector3d& x, int reach, F&& f) const {
    const auto c = cell_of(x);
    for (int i = -reach; i <= reach; ++i)
      for (int j = -reach; j <= reach; ++j)
        for (int k = -reach; k <= reach; ++k) {
          const auto it = cells_.find(key({c[0] + i, c[1] + j, c[2] + k}));
          if (it == cells_.end()) continue;
          for (std::size_t id : it->second) f(id);
        }
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Eigen::Vector3d& x) const {
    return {static_cast<std::int64_t>(std::floor(x.x() / cell_)), static_cast<std::int64_t>(std::floor(x.y() / cell_)),
            static_cast<std::int64_t>(std::floor(x.z() / cell_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0] & 0x1fffff) << 42) | (static_cast<std::uint64_t>(c[1] & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(c[2] & 0x1fffff);
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

// The radius of the largest ball inside the body that touches the surface at x from inside
// (centre x - D n): no surface point nearer its centre than its radius. It is the local
// half-thickness of a plate, the radius of a sphere, the distance to a sharp edge; capped at
// `cap_m`. The cloud must be dense compared with D; 2 % slack absorbs its spacing.
double inscribed_radius_m(const KdTree& cloud, const Eigen::Vector3d& x, const Eigen::Vector3d& n, double cap_m) {
  auto fits = [&](double t) { return !cloud.any_within(x - t * n, 0.98 * t); };
  if (fits(cap_m)) return cap_m;
  double lo = 0, hi = cap_m;
  for (int it = 0; it < 30 && hi - lo > 0.01 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

// ---- the sources' field -------------------------------------------------------------------------

// G = e^{-ikr} / 4 pi r and, with e = (x - y) / r: dG/dn = G' e.n; the dipole a.grad_y G = -G' a.e
// and its normal derivative -[G'' (a.e)(e.n) + G' (a.n - (a.e)(e.n)) / r], where
// G' = -(1 + ikr) G / r, G'' = (2 + 2ikr - k^2 r^2) G / r^2.
struct PairField {
  std::complex<double> g, dg, d, dd;
};
inline PairField pair_field(double k, const Eigen::Vector3d& x, const Eigen::Vector3d& n, const Eigen::Vector3d& y,
                            const Eigen::Vector3d& a) {
  const Eigen::Vector3d diff = x - y;
  const double r = diff.norm();
  const Eigen::Vector3d e = diff / r;
  const double kr = k * r;
  const std::complex<double> g = std::complex<double>(std::cos(kr), -std::sin(kr)) / (4 * kPi * r);
  const std::complex<double> g1 = -(1.0 + kI * kr) * g / r;
  const double en = e.dot(n);
  PairField out{g, g1 * en, 0.0, 0.0};
  if (a.squaredNorm() > 0) {
    const std::complex<double> g2 = std::complex<double>(2 - kr * kr, 2 * kr) * g / (r * r);
    const double ae = a.dot(e);
    out.d = -g1 * ae;
    out.dd = -(g2 * ae * en + g1 * (a.dot(n) - ae * en) / r);
  }
  return out;
}

// ---- spread sources ----------------------------------------------------------------------------

// A mid-surface source is spread over a disk across its axis: its centre (share 1/4) and 6
// points at `spread` from it (1/8 each). Mid-surface sources are as shallow as the plate is half
// thick but a spacing apart that the cost allows; as points they would leave spikes on the
// faces with nothing between (measured on the 6 mm plate: residual 110 %), spread they overlap.
template <class F>
void for_each_point(const Eigen::Vector3d& y, const Eigen::Vector3d& axis, double spread, F&& f) {
  if (spread <= 0) {
    f(y, 1.0);
    return;
  }
  const Eigen::Vector3d e = std::abs(axis.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = axis.cross(e).normalized(), t2 = axis.cross(t1);
  f(y, 0.25);
  for (int i = 0; i < 6; ++i) {
    const double angle = kPi * i / 3;
    f(y + spread * (std::cos(angle) * t1 + std::sin(angle) * t2), 0.125);
  }
}

// ---- the layout -----------------------------------------------------------------------------------

struct Candidate {
  Eigen::Vector3d foot, inward;
  double ball_m;  // inscribed radius D at the foot
};

struct Layout {
  std::vector<Eigen::Vector3d> position, axis;
  std::vector<double> depth, spacing, spread;
  int unknowns = 0, dipoles = 0;
  double floor_m = 0;
};

// One layout for depth factor f: per candidate, thick (depth f D, spacing min(cap, f D)) unless
// two layers f D deep would be nearer each other, 2 (1 - f) D, than their spacing: then thin
// (depth D, on the mid-surface, monopole and dipole). Spacings never below floor_m. Greedy by
// depth: the deepest candidates first, each kept if no kept source is nearer than its spacing.
// A greedy disk packing leaves its points ~1.25x its exclusion radius apart on average; this
// brings the mean spacing back to the target.
constexpr double kPacking = 0.8;

// The fit's rows never exceed this many per unknown (the QR costs rows x unknowns^2): a thin
// plate's mid-surface sources are shallower than its cells can follow, and its residual says so.
constexpr double kMaxCellsPerUnknown = 4;

Layout greedy_layout(const std::vector<Candidate>& cand, const std::vector<std::size_t>& order_by_ball, double f,
                     double cap_m, double floor_m, double min_depth_m) {
  Layout out;
  out.floor_m = floor_m;
  HashGrid grid(std::max(cap_m, floor_m));
  std::vector<double> spacing;
  for (std::size_t c : order_by_ball) {
    const Candidate& q = cand[c];
    const double thick_spacing = std::max(floor_m, std::min(cap_m, f * q.ball_m));
    const bool thin = 2 * (1 - f) * q.ball_m < thick_spacing;
    const double depth = thin ? q.ball_m : f * q.ball_m;
    if (depth < min_depth_m) continue;
    const double s = thin ? std::max(floor_m, std::min(cap_m, q.ball_m)) : thick_spacing;
    const Eigen::Vector3d y = q.foot + depth * q.inward;
    bool free = true;
    grid.for_near(y, 1, [&](std::size_t id) {
      if (free && (out.position[id] - y).norm() < kPacking * std::min(s, spacing[id])) free = false;
    });
    if (!free) continue;
    grid.insert(y, out.position.size());
    out.position.push_back(y);
    out.axis.push_back(thin ? q.inward : Eigen::Vector3d::Zero());
    out.depth.push_back(depth);
    spacing.push_back(s);
    out.spacing.push_back(s);
    out.spread.push_back(0.0);
    out.unknowns += thin ? 2 : 1;
    out.dipoles += thin ? 1 : 0;
  }
  return out;
}

// ---- fit cells ----------------------------------------------------------------------------------

// The dense points grouped into cells about `spacing_m` wide (greedy centres, each point to the
// nearest centre facing the same way, so a thin plate's two faces never share a cell). A row of
// the fit is a cell's area average, so the data's C0 kinks are integrated, not sampled.
std::vector<int> cells_of(const MeshSurfacePoints& dense, double spacing_m, int* cell_count) {
  HashGrid grid(spacing_m);
  std::vector<std::size_t> centres;
  std::vector<int> cell(dense.size(), -1);
  for (std::size_t i = 0; i < dense.size(); ++i) {
    bool covered = false;
    grid.for_near(dense.position_m[i], 1, [&](std::size_t c) {
      const std::size_t at = centres[c];
      if (!covered && (dense.position_m[at] - dense.position_m[i]).norm() < spacing_m &&
          dense.normal[at].dot(dense.normal[i]) > 0.3)
        covered = true;
    });
    if (covered) continue;
    grid.insert(dense.position_m[i], centres.size());
    centres.push_back(i);
  }
  for (std::size_t i = 0; i < dense.size(); ++i) {
    double best = INFINITY;
    grid.for_near(dense.position_m[i], 1, [&](std::size_t c) {
      const std::size_t at = centres[c];
      const double d = (dense.position_m[at] - dense.position_m[i]).norm();
      if (d < best && dense.normal[at].dot(dense.normal[i]) > 0.3) best = d, cell[i] = static_cast<int>(c);
    });
    if (cell[i] < 0) throw std::logic_error("mesh transfer: a surface point without a fit cell");
  }
  *cell_count = static_cast<int>(centres.size());
  return cell;
}

double total_area_m2(const MeshSurfacePoints& p) { return std::accumulate(p.weight_m2.begin(), p.weight_m2.end(), 0.0); }

struct Fit {
  Eigen::VectorXcd strengths;  // per source: its monopole, then (thin ones) its dipole, in order
  double amplification = 0;
};

// Column order: source j's monopole at column[j].first, its dipole (if any) at column[j].second.
std::vector<std::pair<int, int>> columns_of(const Layout& layout) {
  std::vector<std::pair<int, int>> col;
  int next = 0;
  for (const auto& a : layout.axis) {
    const int mono = next++;
    col.emplace_back(mono, a.squaredNorm() > 0 ? next++ : -1);
  }
  return col;
}

Fit fit_layout(double k, const Layout& layout, const MeshSurfacePoints& dense, const std::vector<double>& g_dense,
               const std::vector<int>& cell, int cells, const std::vector<double>& point_scale) {
  const auto col = columns_of(layout);
  Eigen::MatrixXcd a = Eigen::MatrixXcd::Zero(cells, layout.unknowns);
  Eigen::VectorXcd b = Eigen::VectorXcd::Zero(cells);
  std::vector<double> area(static_cast<std::size_t>(cells), 0.0);
  for (std::size_t i = 0; i < dense.size(); ++i) area[static_cast<std::size_t>(cell[i])] += dense.weight_m2[i];
  // Row c: sqrt(W_c) times the area average over the cell, sum_i w_i (.)_i / sqrt(W_c).
  for (std::size_t j = 0; j < layout.position.size(); ++j)
    for (std::size_t i = 0; i < dense.size(); ++i) {
      const auto c = static_cast<Eigen::Index>(cell[i]);
      const double w = point_scale[i] * dense.weight_m2[i] / std::sqrt(area[static_cast<std::size_t>(c)]);
      std::complex<double> dg = 0, dd = 0;
      for_each_point(layout.position[j], layout.axis[j], layout.spread[j], [&](const Eigen::Vector3d& y, double share) {
        const PairField pf = pair_field(k, dense.position_m[i], dense.normal[i], y, layout.axis[j]);
        dg += share * pf.dg;
        dd += share * pf.dd;
      });
      a(c, col[j].first) += w * dg;
      if (col[j].second >= 0) a(c, col[j].second) += w * dd;
    }
  for (std::size_t i = 0; i < dense.size(); ++i)
    b(cell[i]) += point_scale[i] * dense.weight_m2[i] / std::sqrt(area[static_cast<std::size_t>(cell[i])]) * g_dense[i];
  Fit fit;
  fit.strengths = solve_regularized_least_squares(a, b);
  const double bn = b.norm();
  fit.amplification = bn > 0 ? a.norm() * fit.strengths.norm() / bn : 0.0;
  return fit;
}

MeshSources sources_of(double k, const Layout& layout, const Fit& fit) {
  MeshSources s;
  s.k_rad_m = k;
  s.position_m = layout.position;
  s.dipole_axis = layout.axis;
  s.spread_m = layout.spread;
  const auto col = columns_of(layout);
  for (std::size_t j = 0; j < col.size(); ++j) {
    s.monopole.push_back(fit.strengths(col[j].first));
    s.dipole.push_back(col[j].second >= 0 ? fit.strengths(col[j].second) : 0.0);
  }
  return s;
}

// The expansion about the origin: monopoles by the addition theorem (add_monopole); a dipole
// a.grad_y G as the derivative of a monopole's coefficients along a, by central differences
// (step 1e-5 of the scale: truncation ~1e-10, rounding ~1e-11 of the coefficients).
Multipole expansion_of(const MeshSources& s, double tail_tolerance) {
  double rho = 0;
  for (const auto& y : s.position_m) rho = std::max(rho, y.norm());
  const double k = s.k_rad_m;
  const int order = source_order(k, rho);
  Multipole m;
  m.k_rad_m = k;
  m.order = order;
  m.coefficients.assign(static_cast<std::size_t>(harmonic_count(order)), 0.0);
  const double h = 1e-5 * std::max(rho, 1 / k);
  for (std::size_t j = 0; j < s.position_m.size(); ++j)
    for_each_point(s.position_m[j], s.dipole_axis[j], s.spread_m[j], [&](const Eigen::Vector3d& y, double share) {
      add_monopole(k, order, y, share * s.monopole[j], m.coefficients);
      if (s.dipole[j] != 0.0) {
        const std::complex<double> q = share * s.dipole[j] / (2 * h);
        add_monopole(k, order, y + h * s.dipole_axis[j], q, m.coefficients);
        add_monopole(k, order, y - h * s.dipole_axis[j], -q, m.coefficients);
      }
    });
  m.order = truncation_order(m.coefficients, order, tail_tolerance);
  m.coefficients.resize(static_cast<std::size_t>(harmonic_count(m.order)));
  return m;
}

double boundary_residual(const MeshSources& s, const MeshSurfacePoints& check, const std::vector<double>& g_check) {
  double err = 0, norm = 0;
  for (std::size_t i = 0; i < check.size(); ++i) {
    const auto f = s.field(check.position_m[i], check.normal[i]);
    err += check.weight_m2[i] * std::norm(f.normal_derivative - g_check[i]);
    norm += check.weight_m2[i] * g_check[i] * g_check[i];
  }
  return norm > 0 ? std::sqrt(err / norm) : 0.0;
}

std::vector<double> neumann_data(const MeshSurfacePoints& p, double scale) {
  std::vector<double> g(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) g[i] = scale * p.displacement_m[i].dot(p.normal[i]);
  return g;
}

}  // namespace

MeshSources::Field MeshSources::field(const Eigen::Vector3d& x, const Eigen::Vector3d& n) const {
  Field out{0.0, 0.0};
  for (std::size_t j = 0; j < position_m.size(); ++j)
    for_each_point(position_m[j], dipole_axis[j], spread_m[j], [&](const Eigen::Vector3d& y, double share) {
      const PairField pf = pair_field(k_rad_m, x, n, y, dipole_axis[j]);
      out.pressure += share * (monopole[j] * pf.g + dipole[j] * pf.d);
      out.normal_derivative += share * (monopole[j] * pf.dg + dipole[j] * pf.dd);
    });
  return out;
}

MeshSurfacePoints mesh_surface_points(std::span<const std::array<double, 3>> nodes_m,
                                      std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shape,
                                      double spacing_m) {
  return sample_surface(nodes_m, faces, shape, spacing_m, Rule::kThreePoint);
}

MeshTransfer solve_mesh_mode_transfer(std::span<const std::array<double, 3>> nodes_m,
                                      std::span<const std::array<std::int32_t, 6>> faces, std::span<const double> shape,
                                      double omega_rad_s, const model::TransferSettings& settings,
                                      const MeshTransferOptions& options) {
  if (shape.size() != 3 * nodes_m.size()) throw std::invalid_argument("mesh transfer: shape is not [node][3]");
  if (faces.empty() || !(omega_rad_s > 0)) throw std::invalid_argument("mesh transfer: no faces, or omega <= 0");
  const double k = omega_rad_s / settings.sound_speed_m_s;
  const double scale = settings.air_density_kg_m3 * omega_rad_s * omega_rad_s;  // dp/dn = rho omega^2 u.n
  const double lambda = 2 * kPi / k;
  const double data_spacing = surface_node_spacing_m(nodes_m, faces);
  // The sources' spacing: lambda / sources_per_wavelength resolves every order the field carries
  // at that radius, 2 node spacings every detail the data carry (docs/transfer.md).
  const double cap = std::min(lambda / settings.sources_per_wavelength, 2 * data_spacing);

  // The dense cloud: candidates for sources and the inscribed balls' test set, a third of the
  // finest source spacing apart (and one per face at least).
  const double dense_spacing = cap / 3;
  const MeshSurfacePoints dense = sample_surface(nodes_m, faces, shape, dense_spacing, Rule::kCentroid);
  const double area = total_area_m2(dense);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < dense.size(); ++i) centroid += dense.weight_m2[i] * dense.position_m[i];
  centroid /= area;
  double radius = 0;
  for (const auto& x : dense.position_m) radius = std::max(radius, (x - centroid).norm());

  const KdTree tree(dense.position_m);
  std::vector<Candidate> cand(dense.size());
  for (std::size_t i = 0; i < dense.size(); ++i)
    cand[i] = {dense.position_m[i], -dense.normal[i],
               inscribed_radius_m(tree, dense.position_m[i], dense.normal[i], radius)};
  std::vector<std::size_t> order(cand.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cand[a].ball_m > cand[b].ball_m; });
  std::vector<double> balls;
  for (const auto& c : cand) balls.push_back(c.ball_m);
  std::nth_element(balls.begin(), balls.begin() + static_cast<std::ptrdiff_t>(balls.size() / 2), balls.end());
  const double median_ball = balls[balls.size() / 2];
  // Sources shallower than this are dropped (near sharp edges, where D -> 0): the fit cells must
  // be finer than the shallowest source (below), so shallow sources cost rows everywhere; the
  // deeper neighbours cover the edge. A plate keeps its mid-surface (half the median ball).
  const double min_depth = std::min(0.5 * cap, 0.5 * median_ball);

  MeshTransfer best;
  best.boundary_residual = INFINITY;
  double previous = INFINITY;
  int attempt = 0;
  Layout last;
  for (double f : settings.source_depths) {
    // The ceiling: raise the floor on the spacing until the unknowns fit.
    double floor_m = 0;
    Layout layout = greedy_layout(cand, order, f, cap, floor_m, min_depth);
    if (layout.unknowns > options.max_unknowns) floor_m = std::sqrt(area / options.max_unknowns) * 0.5;
    while (layout.unknowns > options.max_unknowns) {
      layout = greedy_layout(cand, order, f, cap, floor_m, min_depth);
      floor_m *= 1.1;
    }
    // An all-thin body (every source on the mid-surface) has the same layout at every factor.
    if (attempt > 0 && layout.position == last.position) break;
    // Spread the mid-surface sources over half their spacing, less where a spread point would come
    // nearer the surface than half the source's depth on the way out from the centre (a rim).
    for (std::size_t j = 0; j < layout.position.size(); ++j) {
      if (layout.axis[j].squaredNorm() == 0) continue;
      for (double r = 0.5 * layout.spacing[j]; r > 0.1 * layout.spacing[j]; r *= 0.5) {
        bool inside = true;
        for_each_point(layout.position[j], layout.axis[j], r, [&](const Eigen::Vector3d& y, double) {
          for (int step = 1; step <= 4 && inside; ++step)
            if (tree.any_within(layout.position[j] + 0.25 * step * (y - layout.position[j]), 0.5 * layout.depth[j])) inside = false;
        });
        if (inside) {
          layout.spread[j] = r;
          break;
        }
      }
    }
    last = layout;
    ++attempt;
    // Fit cells: fit_points_per_unknown per unknown at least, and points_per_source per source spacing.
    // And no wider than the shallowest source is deep: a source's footprint on the surface is
    // about its depth wide, and cell averages coarser than that leave combinations of shallow
    // sources that average to nothing over every cell but not pointwise (measured: residuals of
    // 100-300 % on a cylinder with cells twice its shallowest sources' depth).
    const double shallowest = layout.depth.empty() ? cap : *std::min_element(layout.depth.begin(), layout.depth.end());
    const double cell_spacing = std::min({std::max(cap, layout.floor_m) / settings.points_per_source,
                                          std::sqrt(area / (options.fit_points_per_unknown * layout.unknowns)),
                                          std::max(0.8 * shallowest, std::sqrt(area / (kMaxCellsPerUnknown * layout.unknowns)))});
    // The cells' own points (half a cell apart, one per face at least): the fit's matrix costs
    // their number times the unknowns, so they follow the cells, not the candidates' cloud.
    const MeshSurfacePoints fit_points = sample_surface(nodes_m, faces, shape, cell_spacing / 2, Rule::kCentroid);
    int cells = 0;
    const auto cell = cells_of(fit_points, cell_spacing, &cells);
    // Near a sharp edge (inscribed ball smaller than the spacing, or than a plate's half-thickness)
    // u.n jumps, which no field of sources a spacing deep can follow; at full weight the misfit
    // there rings over the faces (translating cylinder: 21 % error 2 cm from the rims, far field
    // 42 % off); weighted by D / reference it stays at the edge (9 %, 14 %; with a finer mesh
    // 2.4 %, 2.3 %). The boundary residual is still measured at full weight.
    std::vector<double> point_scale(fit_points.size(), 1.0);
    const double edge_reference = std::min(cap, median_ball);
    for (std::size_t i = 0; i < fit_points.size(); ++i)
      point_scale[i] =
          inscribed_radius_m(tree, fit_points.position_m[i], fit_points.normal[i], edge_reference) / edge_reference;
    const Fit fit = fit_layout(k, layout, fit_points, neumann_data(fit_points, scale), cell, cells, point_scale);
    auto sources = std::make_shared<MeshSources>(sources_of(k, layout, fit));
    // The check points: an independent rule (no dense point among them), about as many as cells x 3.
    const bool fine_mesh = faces.size() > static_cast<std::size_t>(cells);
    const MeshSurfacePoints check = sample_surface(nodes_m, faces, shape, fine_mesh ? INFINITY : std::sqrt(area / cells),
                                                   fine_mesh ? Rule::kOffCentre : Rule::kThreePoint);
    const std::vector<double> g_check = neumann_data(check, scale);
    const double residual = boundary_residual(*sources, check, g_check);
    double motion2 = 0, normal2 = 0;
    for (std::size_t i = 0; i < check.size(); ++i) {
      motion2 += check.weight_m2[i] * check.displacement_m[i].squaredNorm();
      normal2 += check.weight_m2[i] * g_check[i] * g_check[i];
    }
    if (residual < best.boundary_residual) {
      best.boundary_residual = residual;
      best.normal_fraction = motion2 > 0 ? std::sqrt(normal2) / (scale * std::sqrt(motion2)) : 0.0;
      best.expansion = expansion_of(*sources, settings.tail_tolerance);
      best.amplification = fit.amplification;
      std::vector<double> depths = layout.depth;
      std::nth_element(depths.begin(), depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2), depths.end());
      best.source_depth_m = depths.empty() ? 0.0 : depths[depths.size() / 2];
      best.source_spacing_m = std::max(cap, layout.floor_m);
      best.sources = static_cast<int>(layout.position.size());
      best.dipoles = layout.dipoles;
      best.fit_points = cells;
      best.check_points = static_cast<int>(check.size());
      best.solution = std::move(sources);
    }
    best.attempts = attempt;
    // As the ellipsoid's solver (mode_transfer.cpp): judged against the surface motion, and a
    // second depth that did not halve the residual ends the search (the floor is the data's).
    if (best.boundary_residual * best.normal_fraction <= settings.residual_target) break;
    if (attempt > 1 && residual > 0.5 * previous) break;
    previous = residual;
  }
  return best;
}

}  // namespace clatter::kernels::transfer
