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
  std::vector<double> radii_m;                         // the M stored radii, ascending
  std::vector<std::array<double, 3>> directions;       // octant direction vertices (45)
  std::vector<std::array<std::int32_t, 3>> triangles;  // their triangles (64)

  // Values per kept coefficient: the far field and one residual per radius.
  std::size_t values() const { return radii_m.size() + 1; }
};

// One proxy ellipsoid (A, B, C): per field 1..6, one SparseTerms per direction, or none when the
// field was not solved. Each direction's series are aligned by the support distance
// (kernels/pan/fit.hpp support_delay_samples), which follows from A, B, C: nothing stored.
struct PanProxy {
  double b_m = 0, c_m = 0;
  std::array<std::vector<SparseTerms>, 6> fields;  // fields[field - 1]

  const std::vector<SparseTerms>& field(int f) const { return fields.at(static_cast<std::size_t>(f - 1)); }
  bool solved(int f) const { return !field(f).empty(); }
};

struct PanBank {
  PanBankHeader header;
  std::vector<PanProxy> proxies;
  SweepStatus sweep;
};

// One task of a PAN sweep: one field of one proxy, before quantization (sweep result files).
struct PanTaskResult {
  std::uint32_t proxy = 0;  // index in the config's proxy list
  double b_m = 0, c_m = 0;
  int field = 0;
  std::vector<SparseTerms> directions;
};

}  // namespace clatter::model
