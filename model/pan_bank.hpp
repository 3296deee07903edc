#pragma once
// The PAN soundbank (Chadwick et al. 2012, sections 4-5) as plain data: the one definition that
// io/ reads and writes (format "clatter-pan-bank", docs/bank-format.md), kernels/pan fits and
// evaluates, synth/ renders from and banks/pan/ builds. Numbers and vectors only; std only.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "model/sweep_status.hpp"

namespace clatter::model {

// Sparse wavelet coefficients of one direction of one field: per kept coefficient j, the radial
// model's values (kernels/pan/radial.hpp), the far field F^j and the residuals R_i p^j(R_i) - F^j.
struct SparseTerms {
  std::vector<std::uint32_t> index;  // kept coefficient j, ascending
  std::vector<float> value;          // [index.size()][M + 1]: F^j, D_1^j .. D_M^j
};

// What every proxy of a bank shares.
struct PanBankHeader {
  double c_m_s = 0, rho_kg_m3 = 0, h_s = 0;
  double dt_s = 0;           // sample interval of the stored series (1 / sample rate)
  double t_first_s = 0;      // retarded time t - R/c of sample 0; t = 0 is the centre of psi
  double epsilon = 0;        // compression threshold of the fit
  double a_m = 0.5;          // semi-axis A shared by every proxy
  std::uint32_t length = 0;  // T, wavelet length (a power of two)
  std::vector<double> radii_m;  // the M stored radii, ascending
  // Every field's direction set refines the same layout (PanDirections) on the same lattice.
  std::int32_t divisions = 8;   // the layout: octant edges cut in 8 -> 45 directions (the paper's)
  std::int32_t max_levels = 0;  // splits below a root the lattice has room for
  std::int32_t lattice() const { return divisions << max_levels; }

  // Values per kept coefficient: the far field and one residual per radius.
  std::size_t values() const { return radii_m.size() + 1; }
};

// A point (a, b) of the direction lattice: the direction (a, b, L - a - b) / |.|, L = lattice().
struct LatticePoint {
  std::int32_t a = 0, b = 0;
  bool operator==(const LatticePoint&) const = default;
};

// The direction set of one field of one proxy (kernels/pan/direction_mesh.hpp): the layout's
// six-node quadratic elements as roots, each split in four where interpolation missed the field.
// Unrefined, it is the paper's uniform layout. Vertices are numbered as they were made: the
// layout's first, then each split's new ones in the order of its children's nodes.
struct PanDirections {
  std::vector<LatticePoint> vertices;
  std::vector<std::array<std::int32_t, 6>> elements;  // corners 0-2, then midpoints of edges 01, 12, 20
  std::vector<std::int32_t> first_child;              // per element: the first of its four children, or -1
};

// How an element splits: child c's corners are its parent's nodes kChildCorners[c] (nodes 0-2 the
// corners, 3-5 the midpoints of edges 01, 12, 20); a child's own nodes are its corners, then the
// midpoints of its edges 01, 12, 20. The children of (P0, P1, P2; M01, M12, M20) are (P0, M01,
// M20), (M01, P1, M12), (M20, M12, P2) and the centre (M12, M20, M01).
inline constexpr std::array<std::array<int, 3>, 4> kChildCorners{{{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {4, 5, 3}}};

// One field of one proxy: its direction set and one SparseTerms per vertex of it; empty when the
// field was not solved.
struct PanField {
  PanDirections directions;
  std::vector<SparseTerms> terms;  // terms[v]: vertex v of `directions`
  bool solved() const { return !terms.empty(); }
};

// A field's held-out check, made when the bank is merged (banks/pan/pan_job.hpp): the bank's
// field, as a reader decodes it, against the same solve's raw field heard through the Kirchhoff
// surface at points that are no stored direction or radius. Empty when the check was off.
struct PanHeldOut {
  std::vector<std::array<double, 3>> points_m;
  std::vector<double> error;   // per point: relative L2 over time, bank against raw
  std::vector<double> raw_l2;  // per point: the raw series' L2 [Pa per unit acceleration]
};

// An entry solved around a closed triangle mesh instead of an ellipsoid (clatter-bank pan-object,
// 000 section 5's per-object PAN): the mesh as given, moved to its centre of mass and scaled so
// that its bounding sphere about that centre has the bank's radius A (the normalized mesh, in the
// given mesh's axes). A scene's object whose mesh is the given one is then the entry scaled by
// beta = 1 / scale (eq. 10), as an object is its proxy scaled.
struct PanMeshBody {
  std::string key;                          // io::mesh_hash of the mesh as given: what a scene's object is matched by
  double scale = 0;                         // normalized = scale (given - centre_of_mass_m)
  std::array<double, 3> centre_of_mass_m{};  // of the uniform solid, in the given mesh's coordinates
  // Normalized vertices of the mesh that are farthest along some direction (convex-hull vertices):
  // the support distance in direction d is max_k d . x_k (kernels/pan/fit.hpp).
  std::vector<std::array<double, 3>> support_points_m;
  // 1: mirror-symmetric in the three planes, one octant of directions per field (eqs. 16-21 give
  // the rest), stored over the symmetry zeros like a proxy's; 8: no such symmetry (solved in the
  // full domain), every octant its own direction sets, the field stored as it is.
  std::int32_t octants = 1;
  bool operator==(const PanMeshBody&) const = default;
};

// The octant of direction d: bit a set where d_a < 0 (octant 0 is x, y, z >= 0).
inline int octant_of(const std::array<double, 3>& d) { return (d[0] < 0 ? 1 : 0) | (d[1] < 0 ? 2 : 0) | (d[2] < 0 ? 4 : 0); }
// Direction d of the positive octant in octant o: the axes of o's bits negated.
inline std::array<double, 3> in_octant(const std::array<double, 3>& d, int o) {
  return {o & 1 ? -d[0] : d[0], o & 2 ? -d[1] : d[1], o & 4 ? -d[2] : d[2]};
}

// One entry of a bank and its fields 1..6: a proxy ellipsoid (A, B, C), or a mesh (`mesh`, its key
// set; B = C = 0). Each direction's series are aligned by the body's support distance
// (kernels/pan/fit.hpp support_delay_samples), which follows from A, B, C or the support points.
struct PanProxy {
  double b_m = 0, c_m = 0;
  PanMeshBody mesh;
  bool is_mesh() const { return !mesh.key.empty(); }
  std::array<PanField, 6> fields;  // fields[field - 1]: the positive octant's sets
  // An entry of 8 octants (mesh.octants): octant o = 1..7's sets at other_octants[o - 1]; empty
  // otherwise.
  std::array<std::array<PanField, 6>, 7> other_octants;
  std::array<PanHeldOut, 6> held_out;

  int octants() const { return is_mesh() ? mesh.octants : 1; }
  const PanField& field(int f, int octant = 0) const {
    return octant == 0 ? fields.at(static_cast<std::size_t>(f - 1))
                       : other_octants.at(static_cast<std::size_t>(octant - 1)).at(static_cast<std::size_t>(f - 1));
  }
  PanField& field(int f, int octant = 0) {
    return octant == 0 ? fields.at(static_cast<std::size_t>(f - 1))
                       : other_octants.at(static_cast<std::size_t>(octant - 1)).at(static_cast<std::size_t>(f - 1));
  }
  bool solved(int f) const { return field(f).solved(); }
};

struct PanBank {
  PanBankHeader header;
  std::vector<PanProxy> proxies;
  SweepStatus sweep;
};

// One task of a PAN sweep: one field of one proxy, before quantization (sweep result files).
struct PanTaskResult {
  std::uint32_t proxy = 0;  // index in the config's proxy list (pan-object: its object list)
  double b_m = 0, c_m = 0;
  PanMeshBody mesh;         // a mesh entry's body (key empty for an ellipsoid)
  int field = 0;
  PanField fit;
  std::array<PanField, 7> other_fits;  // an 8-octant entry's octants 1..7 (mesh.octants)
  // The raw field at the held-out points, for the check at the merge (which codes the bank, so a
  // bank merged again with another coding is checked as it is): [point][sample], the solve's samples.
  std::vector<std::array<double, 3>> held_out_points_m;
  std::vector<float> held_out_raw;
};

}  // namespace clatter::model
