// The Python module `clatter` (docs/python.md): its compiled part, `clatter._clatter`. Serial like
// clatter-synth: it links the serial HDF5 and no MPI. Clatter's InputError (bad input, the same
// message the programs print) becomes clatter.InputError, a ValueError.
#include <pybind11/pybind11.h>

#include "core/errors.hpp"
#include "io/linked_libraries.hpp"
#include "python/bindings.hpp"

PYBIND11_MODULE(_clatter, m) {
  namespace py = pybind11;
  m.doc() = "Clatter's synthesizer and soundbanks (docs/python.md)";
  static py::exception<clatter::InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const clatter::InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    }
  });
  m.attr("version") = clatter::io::version_text("clatter (Python)");
  clatter::python::bind_banks(m);
  clatter::python::bind_scene(m);
  clatter::python::bind_synth(m);
}
