#pragma once
// Reading a modal bank back: `clatter-bank info` on a modal bank (serial work, rank 0 prints).
#include <optional>
#include <string>

namespace clatter::jobs {

// Whether `path` is a modal bank (its format attribute); false for any other file.
bool is_modal_bank(const std::string& path);
// A summary (material, settings, one line per entry: axes, modes, range, multiplicities, mesh,
// residual, size, time) or, with `entry`, that entry's modes: index, frequency, damping,
// multiplet and its multiplicity, residual. Throws InputError.
std::string modal_bank_info(const std::string& path, std::optional<std::size_t> entry);

}  // namespace clatter::jobs
