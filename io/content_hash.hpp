#pragma once
// A hash of what an HDF5 file says, not of its bytes: HDF5 files with equal content can differ in
// layout, free space and object timestamps. Objects are visited in name order; each contributes its
// path, its attributes (name order: name, type class and size, value) and, for a dataset, its
// element type, shape and values. FNV-1a, 64 bits: it detects corruption and any difference in
// content, it is not a cryptographic signature.
#include <cstdint>
#include <string>
#include <vector>

#include "io/h5.hpp"
#include "io/text_hash.hpp"

namespace clatter::io {

struct HashExclusions {
  std::vector<std::string> groups;           // subtrees left out, e.g. "/provenance/run"
  std::vector<std::string> root_attributes;  // e.g. the stored hash itself
};

std::uint64_t content_hash(const File& file, const HashExclusions& exclude = {});

}  // namespace clatter::io
