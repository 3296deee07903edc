#pragma once
// numpy views of the C++ data models: read-only, no copy, each keeping its owner (the Python
// object of the bank, entry or render that holds the memory) alive as the array's base.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <vector>

namespace clatter::python {

namespace py = pybind11;

template <class T>
py::array view(const T* data, std::vector<py::ssize_t> shape, py::handle owner) {
  static const T empty{};  // numpy copies from a null pointer; an empty array needs none
  py::array a(py::dtype::of<T>(), std::move(shape), std::vector<py::ssize_t>{}, data ? data : &empty, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

template <class T>
py::array view(const std::vector<T>& v, py::handle owner) {
  return view(v.data(), {static_cast<py::ssize_t>(v.size())}, owner);
}

// [n][N] as an (n, N) array: std::array<T, N> is N contiguous T.
template <class T, std::size_t N>
py::array view(const std::vector<std::array<T, N>>& v, py::handle owner) {
  static_assert(sizeof(std::array<T, N>) == N * sizeof(T));
  return view(reinterpret_cast<const T*>(v.data()), {static_cast<py::ssize_t>(v.size()), static_cast<py::ssize_t>(N)}, owner);
}

// A flat vector seen as rows of `columns`.
template <class T>
py::array view_rows(const std::vector<T>& v, py::ssize_t columns, py::handle owner) {
  const auto rows = columns > 0 ? static_cast<py::ssize_t>(v.size()) / columns : 0;
  return view(v.data(), {rows, columns}, owner);
}

// An (n, 3) float64 array of points, checked: InputError-like ValueError naming `argument`.
std::vector<std::array<double, 3>> points_arg(const py::handle& points, const char* argument);

// A finite number, else ValueError naming `argument`.
double finite_arg(double value, const char* argument);

}  // namespace clatter::python
