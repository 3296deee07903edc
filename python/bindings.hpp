#pragma once
// The parts of the module `clatter._clatter` (python/module.cpp), one file each.
#include <pybind11/pybind11.h>

#include <memory>
#include <optional>

#include "io/scene.hpp"

namespace clatter::python {

namespace py = pybind11;

// A scene as Python holds it: read and checked by io/ (its meshes resolved), and once modal sound
// asks for them, a copy with the base frequencies of its mesh objects (a FEM each, so kept).
struct PyScene {
  io::Scene scene;
  std::optional<io::Scene> with_frequencies;
  const io::Scene& for_render(bool modal_sound);
};

void bind_banks(py::module_& m);
void bind_scene(py::module_& m);
void bind_synth(py::module_& m);

}  // namespace clatter::python
