#include "python/arrays.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/errors.hpp"

namespace clatter::python {

std::vector<std::array<double, 3>> points_arg(const py::handle& points, const char* argument) {
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  } catch (const py::error_already_set&) {
    a = {};
  }
  if (!a) throw InputError(fmt::format("{}: expected an array of points (n, 3) or one point (3,), in metres", argument));
  if (!(a.ndim() == 2 && a.shape(1) == 3) && !(a.ndim() == 1 && a.shape(0) == 3)) {
    std::string shape;
    for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += fmt::format("{}{}", d ? ", " : "", a.shape(d));
    throw InputError(fmt::format("{}: shape ({}): expected (n, 3) points or one point (3,)", argument, shape));
  }
  const py::ssize_t n = a.ndim() == 2 ? a.shape(0) : 1;
  std::vector<std::array<double, 3>> out(static_cast<std::size_t>(n));
  const double* p = a.data();
  for (py::ssize_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const double v = p[3 * i + static_cast<py::ssize_t>(k)];
      if (!std::isfinite(v)) throw InputError(fmt::format("{}[{}]: {} is not a finite coordinate", argument, i, v));
      out[static_cast<std::size_t>(i)][k] = v;
    }
  return out;
}

double finite_arg(double value, const char* argument) {
  if (!std::isfinite(value)) throw InputError(fmt::format("{}: {} is not a finite number", argument, value));
  return value;
}

}  // namespace clatter::python
