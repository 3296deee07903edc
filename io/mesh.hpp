#pragma once
// A closed triangle mesh read from a Wavefront OBJ file, for objects given by their shape.
#include <array>
#include <string>
#include <vector>

namespace clatter::io {

struct TriangleMesh {
  std::vector<std::array<double, 3>> vertices_m;
  std::vector<std::array<int, 3>> triangles;  // 0-based vertex indices
};

// Reads "v x y z" and "f a b c ..." records (a, a/t, a//n or a/t/n; negative indices count back
// from the latest vertex; polygons are split into fans); every other record is ignored. Checks that
// the mesh can bound a solid: finite coordinates, indices in range, no repeated corner, and every
// edge shared by exactly two faces that run along it in opposite directions (closed, manifold,
// consistently oriented). Self-intersection is not checked. InputError names the file and line.
TriangleMesh read_obj(const std::string& path);

// The mesh's content hash, 16 hex digits: FNV-1a over its vertices' coordinates (the doubles'
// bytes) and its triangles' indices, in order. Two files with the same geometry (comments,
// number formatting, normals and texture coordinates aside) hash alike; a moved, scaled or
// renumbered mesh does not. The object bank keys its entries by it (model/object_bank.hpp).
std::string mesh_hash(const TriangleMesh& mesh);

// The mesh as OBJ text that read_obj reads back to the same numbers: "v x y z" lines printed
// shortest round-trip, then "f a b c" lines (1-based). The bytes are a function of the values, so
// the text can name the mesh by its hash.
std::string obj_text(const TriangleMesh& mesh);

}  // namespace clatter::io
