#pragma once
// The object bank file (format "clatter-object-bank", docs/bank-format.md "Object bank file"): the
// settings every entry shares, then one group per object /entries/NNNN (in task order, failed
// tasks absent) with its key, mesh hash, material, mass properties and the modal entry's datasets
// of the modal bank (io/modal_bank.hpp: frequencies, damping, multiplets, residuals, the curved
// surface, shapes, transfer, mesh quality, solve record). The data is model::ObjectBank
// (model/object_bank.hpp). A sweep's task file holds one entry in the same layout under /result.
#include <string>

#include "io/h5.hpp"
#include "model/object_bank.hpp"

namespace clatter::io {

inline constexpr const char* kObjectBankFormat = "clatter-object-bank";
inline constexpr int kObjectBankFormatVersion = 2;  // 2: the modal entry's band and multiplets (modal bank version 3)

// Writes atomically; every dataset shuffled, deflated and Fletcher-32 checksummed. Each entry's
// wall times go under /provenance/run/entries (left out of the content hash).
void write_object_bank(const std::string& path, const model::ObjectBank& bank, const std::string& command,
                       const std::string& config_toml, int n_ranks);
// Reads and checks a bank (format, version, shapes, units, the count check, checksums, keys
// unique); InputError naming the file and what is wrong.
model::ObjectBank read_object_bank(const std::string& path);

// One entry under `group`, cost included (a task file's payload).
void write_object_entry(File& file, const std::string& group, const model::ObjectEntry& entry, bool with_cost = true);
model::ObjectEntry read_object_entry(const File& file, const std::string& group);

}  // namespace clatter::io
