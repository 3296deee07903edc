#pragma once
// The bank kinds clatter-bank builds and reads, in --help order (banks/kind.hpp). A new kind is a
// new folder banks/NAME/ with a BankKind and one line in registry.cpp.
#include <span>
#include <string>

#include "banks/kind.hpp"

namespace clatter::jobs {

std::span<const BankKind* const> bank_kinds();

// The kind named `name` (a manifest's or --kind's); InputError naming `where` and the known kinds.
const BankKind& kind_named(const std::string& name, const std::string& where);
// The kind of a bank file, by its `format` attribute; InputError when it is no bank of a known kind.
const BankKind& kind_of_file(const std::string& path);

}  // namespace clatter::jobs
