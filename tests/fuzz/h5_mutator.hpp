#pragma once
// Structure-aware fuzzing of Clatter's HDF5 readers. Raw bytes mostly exercise libhdf5's own
// parser (and crash inside it: docs/validation.md), so instead a valid file is taken apart into
// items (groups, datasets, attributes: path, element type, shape, values), the fuzz input drives
// mutations of those items, and a well-formed HDF5 file is built from the result through the
// HDF5 API for the reader under test.
#include <fuzzer/FuzzedDataProvider.h>
#include <hdf5.h>

#include <string>
#include <vector>

namespace clatter::fuzz {

// Element types an item can take: the ones Clatter stores, and strings both ways HDF5 has them.
enum class Kind { group, u8, i16, u16, i32, u32, i64, u64, f32, f64, str_var, str_fixed };

struct H5Item {
  std::string object;     // a group's or dataset's path; for an attribute, what it hangs on
  std::string attribute;  // empty unless an attribute
  Kind kind = Kind::group;
  std::vector<hsize_t> dims;  // empty: scalar
  std::vector<double> values;  // numbers (one per element)
  std::vector<std::string> texts;  // strings (one per element)
  bool compressed = false;  // chunked, shuffled, deflated, Fletcher-32 (as Clatter writes its big datasets)
};

// Every group, dataset and attribute of the file at `path`, parents before children.
std::vector<H5Item> take_apart(const std::string& path);
// Applies the mutations the input asks for: delete, retype, reshape, change values or strings,
// copy to a new or an existing name.
void mutate(std::vector<H5Item>& items, FuzzedDataProvider& input);
// Writes `items` as a new HDF5 file at `path`; items HDF5 refuses (a name taken by another kind of
// object, an attribute on a deleted object) are left out.
void build(const std::vector<H5Item>& items, const std::string& path);

}  // namespace clatter::fuzz
