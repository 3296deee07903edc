#include "petsc/options.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "petsc/error.hpp"

namespace clatter::petsc {

Options& Options::set(const std::string& name, const std::string& value) {
  if (name.size() < 2 || name[0] != '-') throw std::invalid_argument("PETSc option '" + name + "' must start with '-'");
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const auto& e) { return e.first == name; });
  if (it == entries_.end())
    entries_.emplace_back(name, value);
  else
    it->second = value;
  return *this;
}

Options& Options::set(const std::string& name, double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return set(name, std::string(text));
}

Options& Options::set(const std::string& name, long long value) { return set(name, std::to_string(value)); }

std::string Options::text() const {
  std::string out;
  for (const auto& [name, value] : entries_) out += value.empty() ? name + "\n" : name + " " + value + "\n";
  return out;
}

ScopedOptions::ScopedOptions(const Options& options, std::string prefix) : prefix_(std::move(prefix)) {
  for (const auto& [name, value] : options.entries()) {
    std::string full = "-" + prefix_ + name.substr(1);
    PetscBool taken = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, full.c_str(), &taken), "PetscOptionsHasName");
    if (taken) throw std::logic_error("PETSc option " + full + " is already set: two solves share a prefix");
    check(PetscOptionsSetValue(nullptr, full.c_str(), value.empty() ? nullptr : value.c_str()), full.c_str());
    names_.push_back(std::move(full));
    plain_.push_back(name);
  }
}

ScopedOptions::~ScopedOptions() {
  for (const std::string& name : names_) PetscOptionsClearValue(nullptr, name.c_str());
}

std::vector<std::string> ScopedOptions::unused() const {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    PetscBool used = PETSC_FALSE;
    // The database stores names without their leading '-'.
    check(PetscOptionsUsed(nullptr, names_[i].c_str() + 1, &used), "PetscOptionsUsed");
    if (!used) names.push_back(plain_[i]);
  }
  return names;
}

}  // namespace clatter::petsc
