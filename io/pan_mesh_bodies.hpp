#pragma once
// The mesh entries of a PAN bank or task file (model::PanMeshBody; docs/bank-format.md "Mesh
// entries"): io/pan_bank.cpp's writer and reader of that group.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "io/h5.hpp"
#include "model/pan_bank.hpp"

namespace clatter::io {

// Per mesh entry, in entry order: its entry index, key, scale, octants and centre of mass, and its
// support points as a CSR. Nothing is written for no mesh (a bank of proxies, a proxy's task).
void write_mesh_bodies(File& file, const std::string& group,
                       const std::vector<std::pair<std::uint32_t, const model::PanMeshBody*>>& meshes);
// The mesh bodies under `group`, if there is one, into entries[entry]; InputError for any
// inconsistency (an entry out of range or named twice, a bad key, scale, octant count or point).
void read_mesh_bodies(const File& file, const std::string& group, std::vector<model::PanMeshBody*> entries);

}  // namespace clatter::io
