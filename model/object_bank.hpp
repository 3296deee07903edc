#pragma once
// The object bank (003 §5.4's direct path; docs/bank-format.md "Object bank file") as plain data:
// the modal model of given objects, each a closed triangle mesh in one material, not scaled. The
// one definition that io/ reads and writes (format "clatter-object-bank"), banks/modal/ builds and
// the synthesizer renders for objects below its proxy threshold. An entry's modal data is a
// model::ModalEntry (the ellipsoid bank's entry), in the object's body frame: the mesh's own axes
// with the origin at its centre of mass, which is the frame of a scene object given by that mesh.
// Numbers and vectors only; std only.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "model/material.hpp"
#include "model/modal_bank.hpp"
#include "model/sweep_status.hpp"

namespace clatter::model {

struct ObjectEntry {
  // What the synthesizer matches a scene object by: the mesh's content hash (io::mesh_hash: its
  // vertices and triangles, not its file's bytes) and the material's name. key = "HASH-MATERIAL".
  std::string key, mesh_hash;
  std::string source;                   // the mesh file it was built from (provenance)
  Material material;                    // as resolved from the material table
  double mass_kg = 0, volume_m3 = 0;    // of the solid the mesh bounds, at the material's density
  std::array<double, 3> centre_m{};     // its centre of mass in the mesh file's coordinates
  double radius_m = 0;                  // the farthest surface node from the centre of mass: the
                                        // multipoles hold beyond this radius
  double min_thickness_m = 0;           // the thinnest part the mesher found (it set the element size)
  std::int64_t curved_edges = 0;        // boundary edges curved onto the smooth surface (the rest: sharp)
  double surface_area_m2 = 0;           // of the mesh
  // frequencies, damping (the entry's material), multiplets, residuals, the curved surface, the
  // mass-normalized shapes, every mode's transfer (multipoles about the centre of mass), mesh
  // quality, the solve's record and cost. `sample` is the entry's index; axes_m holds the half
  // extents of the bounding box about the centre (the reference fields' scale of the basis rule).
  ModalEntry modal;
};

// What every entry shares: the settings that decide its content.
struct ObjectBankHeader {
  ModalSolveSettings solve;              // f_max_multiple unused (the band is absolute: f_max_hz)
  double f_max_hz = 20000;               // every mode from f_1 to here
  double elements_per_wavelength = 0;    // h = shear wavelength at f_max / this
  std::int32_t elements_through_thickness = 0;  // and at most the thinnest part / this
  double proxy_above_hz = 0;             // a scene's objects were taken below this omega_0 / 2 pi
  std::int32_t ranks_per_task = 0;
  std::string solver_libraries;
  TransferSettings transfer;
};

struct ObjectBank {
  ObjectBankHeader header;
  std::vector<ObjectEntry> entries;      // in task order; failed ones absent (/sweep)
  SweepStatus sweep;
};

}  // namespace clatter::model
