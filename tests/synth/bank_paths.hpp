#pragma once
// The banks the CTest fixtures made, from clatter-synth-tests' command line: PAN.h5 [MODAL.h5
// [OBJECT_PAN.h5 MESH.obj]] (the last a pan-object bank of the mesh).
#include <string>

namespace clatter::test {
inline std::string pan_bank_path, modal_bank_path, object_pan_path, object_pan_mesh_path;
}  // namespace clatter::test
