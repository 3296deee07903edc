#pragma once
// Internals shared by io/h5.cpp, io/h5_attributes.cpp and io/h5_parallel.cpp; not for other users.
#include <numeric>
#include <string>
#include <type_traits>

#include "io/h5.hpp"

namespace clatter::io::detail {

// HDF5 prints its error stack to stderr by default; Clatter reports errors itself, in one line.
void silence_hdf5();
std::string hdf5_error_text();  // and clears the stack
[[noreturn]] void fail(const std::string& path, const std::string& what);

template <class T>
hid_t native_type() {
  if constexpr (std::is_same_v<T, float>) return H5T_NATIVE_FLOAT;
  if constexpr (std::is_same_v<T, double>) return H5T_NATIVE_DOUBLE;
  if constexpr (std::is_same_v<T, std::int32_t>) return H5T_NATIVE_INT32;
  if constexpr (std::is_same_v<T, std::int64_t>) return H5T_NATIVE_INT64;
  if constexpr (std::is_same_v<T, std::uint8_t>) return H5T_NATIVE_UINT8;
  if constexpr (std::is_same_v<T, std::uint32_t>) return H5T_NATIVE_UINT32;
  if constexpr (std::is_same_v<T, std::uint64_t>) return H5T_NATIVE_UINT64;
  if constexpr (std::is_same_v<T, std::int16_t>) return H5T_NATIVE_INT16;
  if constexpr (std::is_same_v<T, std::uint16_t>) return H5T_NATIVE_UINT16;
}

inline hsize_t element_count(const Dims& dims) {
  return std::accumulate(dims.begin(), dims.end(), hsize_t{1}, std::multiplies<>());
}

Handle link_create_plist();  // creates intermediate groups

// Every rank writes its block [offset, offset + count) of a dataset of `global_dims`, collectively
// on a parallel file (a rank may own an empty block); then the "units" attribute.
template <Element T>
void write_block(File& file, const std::string& name, const Dims& global_dims, const Dims& offset,
                 const Dims& count, std::span<const T> data, std::string_view units, bool compress);

}  // namespace clatter::io::detail

// Applies X to every element type the io/ templates are instantiated for (h5.cpp,
// h5_attributes.cpp, h5_parallel.cpp): one list, so the three files cannot drift apart.
#define CLATTER_H5_ELEMENT_TYPES(X) \
  X(float) X(double) X(std::int32_t) X(std::int64_t) X(std::uint8_t) X(std::uint32_t) X(std::uint64_t) \
  X(std::int16_t) X(std::uint16_t)
