#pragma once
#include <petscsys.h>

#include <string>
#include <utility>
#include <vector>

namespace clatter::petsc {

// An ordered list of PETSc options ("-st_type" -> "sinvert") built by Clatter from its config.
//
// They reach PETSc through the global database under a prefix of their own, for the length of one
// solve (ScopedOptions), not through a private database (PetscObjectSetOptions): SLEPc's spectrum
// slicing builds an internal EPS, and MUMPS reads its ICNTLs, from the global database whatever
// the parent object was given. The Session keeps the environment and petrc files out of the
// global database, so what it holds during a solve is exactly these entries.
class Options {
 public:
  // Sets (or replaces) one option; `name` starts with '-'. An empty value is a flag.
  Options& set(const std::string& name, const std::string& value = "");
  Options& set(const std::string& name, double value);  // written with 17 significant digits
  Options& set(const std::string& name, long long value);

  // "-name value" one per line, in the order first set: the provenance of a solve.
  std::string text() const;
  const std::vector<std::pair<std::string, std::string>>& entries() const { return entries_; }


 private:
  std::vector<std::pair<std::string, std::string>> entries_;
};

// Puts every entry of `options` into PETSc's global database as "-<prefix><name>" (objects given
// the options prefix `prefix` read them) and takes them out again on destruction.
class ScopedOptions {
 public:
  ScopedOptions(const Options& options, std::string prefix);
  ~ScopedOptions();
  ScopedOptions(const ScopedOptions&) = delete;
  ScopedOptions& operator=(const ScopedOptions&) = delete;

  const std::string& prefix() const { return prefix_; }
  // Entries nobody read, unprefixed: a misspelt name, or one that never reached its object.
  std::vector<std::string> unused() const;

 private:
  std::vector<std::string> names_;  // prefixed
  std::vector<std::string> plain_;
  std::string prefix_;
};

}  // namespace clatter::petsc
