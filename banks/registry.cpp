#include "banks/registry.hpp"

#include <fmt/format.h>

#include <array>

#include "banks/ground/ground_kind.hpp"
#include "banks/modal/modal_kind.hpp"
#include "banks/modal/object_kind.hpp"
#include "banks/pan/pan_kind.hpp"
#include "core/errors.hpp"
#include "io/h5.hpp"

namespace clatter::jobs {
namespace {

std::string known(const char* (BankKind::*field)() const) {
  std::string list;  // each once: pan and pan-object write the same format
  for (const BankKind* k : bank_kinds())
    if (const std::string item = (k->*field)(); (", " + list + ", ").find(", " + item + ", ") == std::string::npos)
      list += (list.empty() ? "" : ", ") + item;
  return list;
}

}  // namespace

std::span<const BankKind* const> bank_kinds() {
  // One line per kind.
  static const std::array<const BankKind*, 5> kinds = {&pan_kind(), &pan_object_kind(), &modal_kind(), &object_kind(),
                                                       &ground_kind()};
  return kinds;
}

const BankKind& kind_named(const std::string& name, const std::string& where) {
  for (const BankKind* k : bank_kinds())
    if (name == k->name()) return *k;
  throw InputError(fmt::format("{}: no bank kind '{}' (known: {})", where, name, known(&BankKind::name)));
}

const BankKind& kind_of_file(const std::string& path) {
  auto file = io::File::open(path);
  if (!io::has_attribute(file, "/", "format"))
    throw InputError(fmt::format("{}: not a Clatter file (no 'format' attribute); expected a bank: {}", path,
                                 known(&BankKind::file_format)));
  const std::string format = io::read_string_attribute(file, "/", "format");
  for (const BankKind* k : bank_kinds())
    if (format == k->file_format()) return *k;
  throw InputError(fmt::format("{}: format '{}' is not a bank's (expected one of {})", path, format,
                               known(&BankKind::file_format)));
}

FileTool BankKind::probe(CLI::App&, const ProbePoint&) const { return {}; }

PlanEstimate BankKind::plan(const io::Config&, const PlanOptions&) const {
  throw InputError(fmt::format("plan: no cost model for a {} bank yet; run a one-task sweep (--set) and scale its "
                               "stage table",
                               name()));
}

}  // namespace clatter::jobs
