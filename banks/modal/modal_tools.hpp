#pragma once
// Reading a modal bank back: `clatter-bank info` on a modal bank (serial work, rank 0 prints).
#include <array>
#include <optional>
#include <span>
#include <string>

#include "model/modal_bank.hpp"

namespace clatter::jobs {

// A summary (material, settings, per entry: axes, modes, range, cluster sizes, mesh, residual,
// size, time, the multiplets by symmetry and the band's guarantee; the coverage of scaled pieces)
// or, with `entry`, that entry's modes: index, frequency, damping, cluster and multiplet with
// their sizes, symmetry order, residual. Throws InputError.
std::string modal_bank_info(const std::string& path, std::optional<std::size_t> entry);

// What the modal and object banks' `info` share: "1x40, 2x6, 5x1" (how many groups of each size,
// the group given per mode: `cluster` or `multiplet`); the band's guarantee in words; an entry's
// modes as CSV (index, frequency, damping, cluster and its size, multiplet and its size, symmetry
// order, residual, transfer order, boundary residual, attempts, sources) with a title line
// (entry_table) or without.
std::string group_sizes(std::span<const std::int32_t> group_of_mode);
// "complete for every mode with exact frequency <= " f_max_name "X Hz given the mesh error <= ..."
std::string band_guarantee(const model::ModalEntry& entry, const std::string& f_max_name);
std::string entry_table(const model::ModalEntry& entry, std::size_t index);
std::string modes_csv(const model::ModalEntry& entry);

// `probe` on a modal bank: |p_i(x)| of every mode of `entry` at the listener x [m] in the proxy
// frame (centre at the origin, axes along x, y, z), per unit modal amplitude, as CSV; with
// `scale` gamma, of the proxy scaled by gamma (frequencies / gamma, M x gamma^-5/2, 003 eq. 9).
std::string modal_probe_csv(const std::string& path, std::size_t entry, const std::array<double, 3>& point_m,
                            double scale);

}  // namespace clatter::jobs
