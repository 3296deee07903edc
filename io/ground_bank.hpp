#pragma once
// The ground soundbank file (format "clatter-ground-bank", docs/bank-format.md "Ground bank"): the
// air the series were computed for (/air), then one group per ground material /materials/<name>
// with its moduli and source, its (elevation, eta) grid and the ragged series of Pi(t_hat)
// concatenated into one `pi` dataset (series_offset, series_length, t_hat_start, dt_hat index it).
// The data is model::GroundBank (model/ground_bank.hpp); the numerics live in kernels/ground. Part
// of the serial io library too: clatter-synth reads it without MPI. A sweep's task file holds one
// (material, elevation) row of series under /result.
#include <string>
#include <vector>

#include "io/h5.hpp"
#include "model/ground_bank.hpp"

namespace clatter::io {

inline constexpr const char* kGroundBankFormat = "clatter-ground-bank";
inline constexpr int kGroundBankFormatVersion = 2;  // 2: the series' tails (docs/bank-format.md)

// Writes atomically (temporary + rename); every dataset shuffled, deflated and Fletcher-32
// checksummed; provenance as the other banks (n_ranks: how many ranks built it, in
// /provenance/run, outside the content hash).
void write_ground_bank(const std::string& path, const model::GroundBank& bank, const std::string& command,
                       const std::string& config_toml, int n_ranks = 1);

// Reads and checks a bank (format, version, every shape, ascending grids, positive dt_hat, finite
// values, offsets inside `pi`, checksums); InputError naming the file and the dataset or attribute.
model::GroundBank read_ground_bank(const std::string& path);

// One task's payload under `group` of a task file: the series of one (material, elevation) for
// every eta of the grid, in eta order. read_ground_task checks the count and every series.
void write_ground_task(File& file, const std::string& group, const std::vector<model::GroundSeries>& row);
std::vector<model::GroundSeries> read_ground_task(const File& file, const std::string& group, std::size_t n_eta);

}  // namespace clatter::io
