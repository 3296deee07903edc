#pragma once
// The parts of the module `clatter._clatter` (python/module.cpp), one file each.
#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>

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

// Clatter's stage log and the serial HDF5 library serve one thread at a time, so every call into
// them runs through `exclusive`: it waits for one lock with the GIL released (other Python threads
// go on meanwhile) and runs `work`, which must return C++ values only (no Python object is touched
// without the GIL).
std::mutex& library_mutex();
template <class Work>
auto exclusive(Work&& work) {
  py::gil_scoped_release unlocked;
  std::lock_guard<std::mutex> lock(library_mutex());
  return work();
}

// "pan", "modal", "object" or "ground" by the file's format attribute; "" for a file without one
// or of another format. InputError for a file HDF5 cannot read. Call it inside `exclusive`.
std::string bank_kind(const std::string& path);

void bind_banks(py::module_& m);
void bind_scene(py::module_& m);
void bind_synth(py::module_& m);

}  // namespace clatter::python
