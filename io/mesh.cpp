#include "io/mesh.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "core/errors.hpp"
#include "io/text_hash.hpp"
#include "io/text_number.hpp"

namespace clatter::io {

TriangleMesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the mesh file");
  TriangleMesh mesh;
  std::vector<int> face_line;  // per triangle, for messages
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream s(line);
    std::string kind;
    if (!(s >> kind)) continue;
    const std::string where = fmt::format("{}:{}", path, n);
    if (kind == "v") {
      std::array<double, 3> v{};
      for (auto& x : v) {
        std::string token;
        if (!(s >> token)) throw InputError(where + ": a vertex needs 3 coordinates");
        x = finite_number(token, "vertex coordinate", where);
      }
      mesh.vertices_m.push_back(v);
    } else if (kind == "f") {
      std::vector<int> corners;
      for (std::string token; s >> token;) {
        char* end = nullptr;
        const long i = std::strtol(token.c_str(), &end, 10);
        if (end == token.c_str() || (*end != 0 && *end != '/')) throw InputError(fmt::format("{}: face corner '{}' is not an index", where, token));
        const long count = static_cast<long>(mesh.vertices_m.size());
        const long index = i > 0 ? i - 1 : count + i;  // OBJ counts from 1; negative: from the end
        if (i == 0 || index < 0 || index >= count)
          throw InputError(fmt::format("{}: face corner {} is not one of the {} vertices read so far", where, token, count));
        corners.push_back(static_cast<int>(index));
      }
      if (corners.size() < 3) throw InputError(where + ": a face needs at least 3 corners");
      for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
        const std::array<int, 3> t{corners[0], corners[k], corners[k + 1]};
        if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
          throw InputError(fmt::format("{}: face repeats vertex {}", where, (t[0] == t[1] || t[0] == t[2] ? t[0] : t[1]) + 1));
        mesh.triangles.push_back(t);
        face_line.push_back(n);
      }
    }
  }
  if (mesh.triangles.size() < 4) throw InputError(fmt::format("{}: {} triangles: a closed mesh needs at least 4", path, mesh.triangles.size()));
  // Closed and consistently oriented: each directed edge once, and its reverse once.
  std::map<std::pair<int, int>, int> edges;  // directed edge -> its face's line
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> e{mesh.triangles[t][static_cast<std::size_t>(k)], mesh.triangles[t][static_cast<std::size_t>((k + 1) % 3)]};
      const auto [it, fresh] = edges.emplace(e, face_line[t]);
      if (!fresh)
        throw InputError(fmt::format("{}:{}: edge {}-{} runs the same way in the face on line {}: faces are inconsistently "
                                     "oriented, or more than two meet at that edge",
                                     path, face_line[t], e.first + 1, e.second + 1, it->second));
    }
  for (const auto& [e, n] : edges)
    if (!edges.count({e.second, e.first}))
      throw InputError(fmt::format("{}:{}: edge {}-{} has no face on its other side: the mesh is not closed", path, n, e.first + 1, e.second + 1));
  return mesh;
}

std::string mesh_hash(const TriangleMesh& mesh) {
  std::string bytes;
  bytes.reserve(mesh.vertices_m.size() * sizeof(double) * 3 + mesh.triangles.size() * sizeof(std::int32_t) * 3);
  for (const auto& v : mesh.vertices_m) bytes.append(reinterpret_cast<const char*>(v.data()), sizeof(double) * 3);
  bytes.append("|");  // vertices end here: a vertex list cannot pass for a triangle list
  for (const auto& t : mesh.triangles)
    for (const int i : t) {
      const auto index = static_cast<std::int32_t>(i);
      bytes.append(reinterpret_cast<const char*>(&index), sizeof index);
    }
  return hash_hex(text_hash(bytes));
}

std::string obj_text(const TriangleMesh& mesh) {
  std::string text;
  text.reserve(48 * mesh.vertices_m.size() + 24 * mesh.triangles.size());
  for (const auto& v : mesh.vertices_m) fmt::format_to(std::back_inserter(text), "v {} {} {}\n", v[0], v[1], v[2]);
  for (const auto& t : mesh.triangles) fmt::format_to(std::back_inserter(text), "f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  return text;
}

}  // namespace clatter::io
