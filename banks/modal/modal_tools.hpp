#pragma once
// Reading a modal bank back: `clatter-bank info` on a modal bank (serial work, rank 0 prints).
#include <array>
#include <optional>
#include <string>

namespace clatter::jobs {

// A summary (material, settings, one line per entry: axes, modes, range, multiplicities, mesh,
// residual, size, time) or, with `entry`, that entry's modes: index, frequency, damping,
// multiplet and its multiplicity, residual. Throws InputError.
std::string modal_bank_info(const std::string& path, std::optional<std::size_t> entry);

// `probe` on a modal bank: |p_i(x)| of every mode of `entry` at the listener x [m] in the proxy
// frame (centre at the origin, axes along x, y, z), per unit modal amplitude, as CSV; with
// `scale` gamma, of the proxy scaled by gamma (frequencies / gamma, M x gamma^-5/2, 003 eq. 9).
std::string modal_probe_csv(const std::string& path, std::size_t entry, const std::array<double, 3>& point_m,
                            double scale);

}  // namespace clatter::jobs
