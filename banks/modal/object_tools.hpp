#pragma once
// Reading an object bank back: `clatter-bank info` and `probe` on it (serial, rank 0 prints).
#include <array>
#include <optional>
#include <string>

namespace clatter::jobs {

// A summary (settings, one line per entry: key, mesh file, material, modes, range, multiplicities,
// mesh, thinnest part, residuals, transfer, time) or, with `entry`, that entry's modes as CSV.
std::string object_bank_info(const std::string& path, std::optional<std::size_t> entry);

// |p_i(x)| of every mode of `entry` at x [m] in the object's body frame (the mesh's axes about its
// centre of mass), per unit modal amplitude, as CSV. InputError inside the entry's radius.
std::string object_probe_csv(const std::string& path, std::size_t entry, const std::array<double, 3>& point_m);

}  // namespace clatter::jobs
