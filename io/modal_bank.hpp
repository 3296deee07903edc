#pragma once
// The modal soundbank file (format "clatter-modal-bank", docs/bank-format.md "Modal bank"): the
// material and settings, then one group per ellipsoid /entries/NNNN (4 digits, in sample order,
// failed samples absent; attribute `sample` is the index in patch.samples) with its frequencies,
// damping, clusters, multiplets by symmetry, residuals, band, curved surface mesh, mass-normalized surface mode shapes, mesh
// quality and solver record. The data is model::ModalBank (model/modal_bank.hpp). A sweep's task
// file holds one entry in the same layout under /result.
#include <string>

#include "io/h5.hpp"
#include "model/modal_bank.hpp"

namespace clatter::io {

inline constexpr const char* kModalBankFormat = "clatter-modal-bank";
// 2: acoustic transfer per mode; 3: a band per entry, the band's guarantee, multiplets by symmetry
inline constexpr int kModalBankFormatVersion = 3;

// Writes atomically; every dataset shuffled, deflated and Fletcher-32 checksummed. Each entry's
// wall times go under /provenance/run/entries (left out of the content hash).
void write_modal_bank(const std::string& path, const model::ModalBank& bank, const std::string& command,
                      const std::string& config_toml, int n_ranks);
// Reads and checks a bank (format, version, every shape and unit, index ranges, ascending
// frequencies, checksums); InputError naming the file and what is wrong.
model::ModalBank read_modal_bank(const std::string& path);

// One entry under `group` (a task file's payload, or a bank's /entries/eNNN), its cost at
// group/cost unless with_cost is false (a bank keeps costs in provenance, out of its content
// hash); read_modal_entry reads the cost when it is there.
void write_modal_entry(File& file, const std::string& group, const model::ModalEntry& entry, bool with_cost = true);
model::ModalEntry read_modal_entry(const File& file, const std::string& group);
void write_modal_entry_cost(File& file, const std::string& group, const model::ModalEntryCost& cost);
model::ModalEntryCost read_modal_entry_cost(const File& file, const std::string& group);
// What the solve settings promise of an entry: residuals within the limit, the count check
// passed, exactly the 6 rigid motions below the interval; InputError naming file and group.
void check_modal_entry_solve(const File& file, const std::string& group, const model::ModalEntry& entry,
                             const model::ModalSolveSettings& solve);

// A material with its Rayleigh damping as the attributes of `group` (name, source, rho_kg_m3,
// youngs_pa, poisson, rayleigh_alpha_1_s, rayleigh_beta_s); read back checked.
void write_material(File& file, const std::string& group, const model::Material& material);
model::Material read_material(const File& file, const std::string& group);

}  // namespace clatter::io
