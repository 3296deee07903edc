#pragma once
// The PAN soundbank file (format "clatter-pan-bank", docs/bank-format.md): per proxy ellipsoid
// (A, B, C) and rigid-body field, the sparse wavelet coefficients of the radial model (the far
// field and the residual at each stored radius, kernels/pan/radial.hpp) in each octant direction. The data is model::PanBank (model/pan_bank.hpp); the numerics live in
// kernels/pan.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/h5.hpp"
#include "model/pan_bank.hpp"

namespace clatter::io {

inline constexpr const char* kPanBankFormat = "clatter-pan-bank";
inline constexpr int kPanBankFormatVersion = 3;  // 3: the radial model replaced the series (8)

// Writes atomically (temporary + rename); coefficients quantized to 16 bits per (direction, value)
// scale, indices delta-coded, every dataset shuffled, deflated and Fletcher-32 checksummed.
void write_pan_bank(const std::string& path, const model::PanBank& bank, const std::string& command,
                    const std::string& config_toml, int n_ranks);

// Reads and checks a bank (format, version, every shape and unit, index ranges, checksums);
// InputError naming the file and what is wrong. The coefficients are dequantized once, here, into
// the form the evaluator reads (kernels/pan/field.hpp).
model::PanBank read_pan_bank(const std::string& path);

// The payload of a task file under group `group` (the sweep engine owns the file). read_pan_task
// checks every shape against the header.
// `values` per kept coefficient: PanBankHeader::values().
void write_pan_task(File& file, const std::string& group, const model::PanTaskResult& task, std::size_t values);
model::PanTaskResult read_pan_task(const File& file, const std::string& group, std::size_t values,
                                   std::size_t n_directions, std::uint32_t length);

// Bytes of coefficient data (indices, values, scales) as stored before compression.
std::size_t pan_coefficient_bytes(const model::PanBank& bank);

}  // namespace clatter::io
