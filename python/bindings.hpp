#pragma once
// The parts of the module `clatter._clatter` (python/module.cpp), one file each.
#include <pybind11/pybind11.h>

#include <memory>

#include "io/scene.hpp"

namespace clatter::python {

namespace py = pybind11;

// A scene as Python holds it: read and checked by io/ (its meshes resolved); the first render
// with modal sound adds the base frequencies of its mesh objects that the scene does not give (a
// FEM each, as clatter-synth's load_scene does for modal sound), kept for later renders. No other
// source reads them.
struct PyScene {
  io::Scene scene;
  bool frequencies_added = false;
  const io::Scene& for_render(bool modal_sound);
};

void bind_banks(py::module_& m);
void bind_scene(py::module_& m);
void bind_synth(py::module_& m);

}  // namespace clatter::python
