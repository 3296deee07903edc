#pragma once
// Reading a modal bank back: `clatter-bank info` on a modal bank (serial work, rank 0 prints).
#include <array>
#include <optional>
#include <string>

#include "model/modal_bank.hpp"

namespace clatter::jobs {

// A summary (material, settings, one line per entry: axes, modes, range, multiplicities, mesh,
// residual, size, time) or, with `entry`, that entry's modes: index, frequency, damping,
// multiplet and its multiplicity, residual. Throws InputError.
std::string modal_bank_info(const std::string& path, std::optional<std::size_t> entry);

// What the modal and object banks' `info` share: "1x40, 2x6, 5x1" (how many multiplets of each
// size), and an entry's modes as CSV (index, frequency, damping, multiplet, multiplicity, residual,
// transfer order, boundary residual, attempts, sources) with a title line (entry_table) or without.
std::string multiplicities(const model::ModalEntry& entry);
std::string entry_table(const model::ModalEntry& entry, std::size_t index);
std::string modes_csv(const model::ModalEntry& entry);

// `probe` on a modal bank: |p_i(x)| of every mode of `entry` at the listener x [m] in the proxy
// frame (centre at the origin, axes along x, y, z), per unit modal amplitude, as CSV; with
// `scale` gamma, of the proxy scaled by gamma (frequencies / gamma, M x gamma^-5/2, 003 eq. 9).
std::string modal_probe_csv(const std::string& path, std::size_t entry, const std::array<double, 3>& point_m,
                            double scale);

}  // namespace clatter::jobs
