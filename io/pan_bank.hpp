#pragma once
// The PAN soundbank file (format "clatter-pan-bank", docs/bank-format.md): per proxy ellipsoid
// (A, B, C) and rigid-body field, the sparse wavelet coefficients of q_1..q_N in each of the 45
// octant directions. Plain data here; the numerics live in kernels/pan.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "io/h5.hpp"

namespace clatter::io {

inline constexpr const char* kPanBankFormat = "clatter-pan-bank";
inline constexpr int kPanBankFormatVersion = 2;

struct PanBankHeader {
  double c_m_s = 0, rho_kg_m3 = 0, h_s = 0;
  double dt_s = 0;           // sample interval of q_k (1 / sample rate)
  double t_first_s = 0;      // retarded time t - R/c of sample 0; t = 0 is the centre of psi
  double epsilon = 0;        // compression threshold of the fit
  double a_m = 0.5;          // semi-axis A shared by every proxy
  int terms = 0;             // N
  std::uint32_t length = 0;  // T, wavelet length
  std::vector<double> radii_m;                      // the M fitted radii
  std::vector<std::array<double, 3>> directions;    // 45 unit vectors
  std::vector<std::array<std::int32_t, 3>> triangles;  // 64
};

struct PanTerms {  // one direction of one field
  std::vector<std::uint32_t> index;  // ascending
  std::vector<float> value;          // [index.size()][terms]
};

struct PanProxy {
  double b_m = 0, c_m = 0;
  std::vector<std::int32_t> delay_steps;        // per direction: alignment advance in samples
  std::array<std::vector<PanTerms>, 6> fields;  // fields 1..6, one PanTerms per direction
};

// How complete the sweep that built the bank was (group /sweep): every proxy x field is a task.
struct SweepStatus {
  std::uint32_t tasks_total = 0;
  std::vector<std::string> failed;   // "task: reason"
  std::vector<std::string> missing;  // tasks never run (interrupted, not in this job's slice)
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
  std::vector<PanTerms> directions;
};

// Writes atomically (temporary + rename); coefficients quantized to 16 bits per (direction, term)
// scale, indices delta-coded, every dataset shuffled, deflated and Fletcher-32 checksummed.
void write_pan_bank(const std::string& path, const PanBank& bank, const std::string& command,
                    const std::string& config_toml, int n_ranks);

// Reads and checks a bank (format, version, every shape and unit, index ranges, checksums);
// InputError naming the file and what is wrong.
PanBank read_pan_bank(const std::string& path);

// The payload of a task file under group `group` (the sweep engine owns the file). read_pan_task
// checks every shape against the header.
void write_pan_task(File& file, const std::string& group, const PanTaskResult& task, int terms);
PanTaskResult read_pan_task(const File& file, const std::string& group, int terms, std::size_t n_directions,
                            std::uint32_t length);

// Bytes of coefficient data (indices, values, scales) as stored before compression.
std::size_t pan_coefficient_bytes(const PanBank& bank);

}  // namespace clatter::io
