#pragma once
// The PAN soundbank file (format "clatter-pan-bank", docs/bank-format.md): per entry (a proxy
// ellipsoid (A, B, C), or a normalized mesh) and rigid-body field, its direction set (kernels/pan/direction_mesh.hpp) and, per
// direction, the sparse wavelet coefficients of the radial model (the far field and the residual at
// each stored radius, kernels/pan/radial.hpp). The data is model::PanBank (model/pan_bank.hpp); the
// numerics live in kernels/pan.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/h5.hpp"
#include "model/pan_bank.hpp"

namespace clatter::io {

inline constexpr const char* kPanBankFormat = "clatter-pan-bank";
// 3: the radial model replaced the series (8); 4: a direction set per (proxy, field), adaptive;
// 5: the values are the field over its symmetry zeros (kernels/pan/directions.hpp symmetry_zeros);
// 6: entries around meshes (/meshes, model::PanMeshBody). Version 5 files are read too.
inline constexpr int kPanBankFormatVersion = 6;

// Writes atomically (temporary + rename); coefficients quantized to 16 bits per (direction, value)
// scale, a refined direction coded as its difference from its parent's interpolation, indices
// delta-coded, every dataset shuffled, deflated and Fletcher-32 checksummed.
void write_pan_bank(const std::string& path, const model::PanBank& bank, const std::string& command,
                    const std::string& config_toml, int n_ranks);

// Reads and checks a bank (format, version, every shape and unit, index ranges, checksums);
// InputError naming the file and what is wrong. The coefficients are dequantized once, here, into
// the form the evaluator reads (kernels/pan/field.hpp).
model::PanBank read_pan_bank(const std::string& path);

// A field as a reader of the bank gets it (quantized, coded and decoded as write_pan_bank and
// read_pan_bank do): what a task checks against held-out points before the merge.
model::PanField stored_field(const model::PanBankHeader& header, const model::PanField& field);

// The payload of a task file under group `group` (the sweep engine owns the file). read_pan_task
// checks every shape against the header (values per kept coefficient, length, the lattice).
void write_pan_task(File& file, const std::string& group, const model::PanTaskResult& task, std::int32_t lattice,
                    std::size_t values);
model::PanTaskResult read_pan_task(const File& file, const std::string& group, const model::PanBankHeader& header);

}  // namespace clatter::io
