#pragma once
// Typed collectives, so callers ship values, vectors and records without packing bytes by hand.
//
// Moving data (broadcast, gather, all_gather) goes as MPI_BYTE with counts in bytes: it works for
// any trivially copyable T (structs with padding, std::array, std::complex) without a derived
// datatype per type, and Clatter runs one binary on one kind of node, so the bytes mean the same
// on every rank. Reductions do arithmetic and need MPI's own datatype of T (mpi_type<T>).
//
// MPI counts are int: a transfer over INT_MAX bytes (or elements, for reductions) throws
// std::length_error, on every rank alike wherever the ranks can know it, never a truncated count.
#include <mpi.h>

#include <array>
#include <climits>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "mpi/comm.hpp"

namespace clatter::mpi {

// Pointers are excluded: their bytes mean nothing on another rank (and a string literal must
// reach the std::string overloads of comm.hpp).
template <class T>
concept Trivial = std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>;

// bool is left out: a logical or over ranks is any().
template <class T>
concept Arithmetic = std::is_arithmetic_v<T> && !std::is_same_v<T, bool>;

template <Arithmetic T>
MPI_Datatype mpi_type() {
  if constexpr (std::is_floating_point_v<T>) {
    if constexpr (std::is_same_v<T, float>) return MPI_FLOAT;
    else if constexpr (std::is_same_v<T, double>) return MPI_DOUBLE;
    else return MPI_LONG_DOUBLE;
  } else if constexpr (std::is_signed_v<T>) {
    if constexpr (sizeof(T) == 1) return MPI_INT8_T;
    else if constexpr (sizeof(T) == 2) return MPI_INT16_T;
    else if constexpr (sizeof(T) == 4) return MPI_INT32_T;
    else return MPI_INT64_T;
  } else {
    if constexpr (sizeof(T) == 1) return MPI_UINT8_T;
    else if constexpr (sizeof(T) == 2) return MPI_UINT16_T;
    else if constexpr (sizeof(T) == 4) return MPI_UINT32_T;
    else return MPI_UINT64_T;
  }
}

namespace detail {
// `count` items of `item_bytes` each as an int count of bytes; std::length_error past INT_MAX.
int byte_count(std::uint64_t count, std::size_t item_bytes, const char* what);
void broadcast_bytes(MPI_Comm comm, void* data, int bytes, int root);
// Broadcasts root's item count; every rank then checks it, so all throw alike.
std::uint64_t broadcast_count(MPI_Comm comm, std::uint64_t count, int root);
// The bytes of every rank's items, concatenated in rank order on root. Returns the item counts by
// rank on root (empty elsewhere).
std::vector<std::uint64_t> gather_bytes(MPI_Comm comm, const void* data, std::uint64_t count, std::size_t item_bytes,
                                        std::vector<unsigned char>& all, int root);
void all_gather_bytes(MPI_Comm comm, const void* data, int bytes, void* all);
void all_reduce(MPI_Comm comm, const void* in, void* out, std::size_t count, MPI_Datatype type, MPI_Op op);
}  // namespace detail

// Root's value on every rank.
template <Trivial T>
T broadcast(MPI_Comm comm, T value, int root = 0) {
  static_assert(sizeof(T) <= INT_MAX);
  detail::broadcast_bytes(comm, &value, static_cast<int>(sizeof(T)), root);
  return value;
}

// Root's vector on every rank, whatever length the others passed in.
template <Trivial T>
std::vector<T> broadcast(MPI_Comm comm, std::vector<T> values, int root = 0) {
  const std::uint64_t n = detail::broadcast_count(comm, values.size(), root);
  const int bytes = detail::byte_count(n, sizeof(T), "broadcast");
  values.resize(static_cast<std::size_t>(n));
  detail::broadcast_bytes(comm, values.data(), bytes, root);
  return values;
}

// On root: every rank's value, indexed by rank; elsewhere: empty.
template <Trivial T>
std::vector<T> gather(MPI_Comm comm, const T& value, int root = 0) {
  std::vector<unsigned char> all;
  const auto counts = detail::gather_bytes(comm, &value, 1, sizeof(T), all, root);
  std::vector<T> out(counts.size());
  if (!out.empty()) std::memcpy(out.data(), all.data(), all.size());
  return out;
}

// On root: every rank's vector (of any length, empty too), indexed by rank; elsewhere: empty.
template <Trivial T>
std::vector<std::vector<T>> gather(MPI_Comm comm, const std::vector<T>& values, int root = 0) {
  std::vector<unsigned char> all;
  const auto counts = detail::gather_bytes(comm, values.data(), values.size(), sizeof(T), all, root);
  std::vector<std::vector<T>> out;
  std::size_t at = 0;
  for (const std::uint64_t n : counts) {
    std::vector<T>& v = out.emplace_back(static_cast<std::size_t>(n));
    if (n > 0) std::memcpy(v.data(), all.data() + at, v.size() * sizeof(T));
    at += v.size() * sizeof(T);
  }
  return out;
}

// Every rank's value on every rank, indexed by rank.
template <Trivial T>
std::vector<T> all_gather(MPI_Comm comm, const T& value) {
  static_assert(sizeof(T) <= INT_MAX);
  std::vector<T> out(static_cast<std::size_t>(size(comm)));
  detail::all_gather_bytes(comm, &value, static_cast<int>(sizeof(T)), out.data());
  return out;
}

namespace detail {
template <Arithmetic T>
T reduce(MPI_Comm comm, T value, MPI_Op op) {
  T out{};
  all_reduce(comm, &value, &out, 1, mpi_type<T>(), op);
  return out;
}
template <Arithmetic T, std::size_t N>
std::array<T, N> reduce(MPI_Comm comm, const std::array<T, N>& values, MPI_Op op) {
  std::array<T, N> out{};
  all_reduce(comm, values.data(), out.data(), N, mpi_type<T>(), op);
  return out;
}
}  // namespace detail

// Reductions over every rank of `comm`, the result on every rank: of a scalar, and element-wise
// of a std::array or a std::vector (the same length on every rank).
template <Arithmetic T>
T all_reduce_sum(MPI_Comm comm, T value) { return detail::reduce(comm, value, MPI_SUM); }
template <Arithmetic T>
T all_reduce_max(MPI_Comm comm, T value) { return detail::reduce(comm, value, MPI_MAX); }
template <Arithmetic T>
T all_reduce_min(MPI_Comm comm, T value) { return detail::reduce(comm, value, MPI_MIN); }
template <Arithmetic T, std::size_t N>
std::array<T, N> all_reduce_sum(MPI_Comm comm, const std::array<T, N>& values) {
  return detail::reduce(comm, values, MPI_SUM);
}
template <Arithmetic T, std::size_t N>
std::array<T, N> all_reduce_max(MPI_Comm comm, const std::array<T, N>& values) {
  return detail::reduce(comm, values, MPI_MAX);
}
template <Arithmetic T>
std::vector<T> all_reduce_sum(MPI_Comm comm, const std::vector<T>& values) {
  std::vector<T> out(values.size());
  detail::all_reduce(comm, values.data(), out.data(), values.size(), mpi_type<T>(), MPI_SUM);
  return out;
}

// True on every rank when `value` is true on any rank of `comm`.
bool any(MPI_Comm comm, bool value);

}  // namespace clatter::mpi
