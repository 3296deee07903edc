#include "io/pan_mesh_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "core/errors.hpp"

namespace clatter::io {

void write_mesh_bodies(File& file, const std::string& group,
                       const std::vector<std::pair<std::uint32_t, const model::PanMeshBody*>>& meshes) {
  if (meshes.empty()) return;
  create_group(file, group);
  std::vector<std::uint32_t> entry, offsets{0}, octants;
  std::vector<double> scale, centre, points;
  std::string keys;
  for (const auto& [e, m] : meshes) {
    if (m->octants != 1 && m->octants != 8) throw std::invalid_argument("PAN mesh entry: octants is neither 1 nor 8");
    octants.push_back(static_cast<std::uint32_t>(m->octants));
    if (m->key.empty() || m->key.find(' ') != std::string::npos)
      throw std::invalid_argument("PAN mesh entry: its key is empty or holds a space");
    entry.push_back(e);
    keys += (keys.empty() ? "" : " ") + m->key;
    scale.push_back(m->scale);
    centre.insert(centre.end(), m->centre_of_mass_m.begin(), m->centre_of_mass_m.end());
    for (const auto& x : m->support_points_m) points.insert(points.end(), x.begin(), x.end());
    offsets.push_back(static_cast<std::uint32_t>(points.size() / 3));
  }
  write_attribute(file, group, "keys", std::string_view(keys));
  write_dataset<std::uint32_t>(file, group + "/entry", entry, {entry.size()}, "1");
  write_dataset<double>(file, group + "/scale", scale, {scale.size()}, "1");
  write_dataset<std::uint32_t>(file, group + "/octants", octants, {octants.size()}, "1");
  write_dataset<double>(file, group + "/centre_of_mass_m", centre, {entry.size(), 3}, "m");
  write_dataset<std::uint32_t>(file, group + "/support_offsets", offsets, {offsets.size()}, "1");
  write_dataset<double>(file, group + "/support_points_m", points, {points.size() / 3, 3}, "m", true);
}

void read_mesh_bodies(const File& file, const std::string& group, std::vector<model::PanMeshBody*> entries) {
  if (!exists(file, group)) return;
  const std::string where = file.path() + ": '" + group + "'";
  Dims n;
  auto entry = read_dataset<std::uint32_t>(file, group + "/entry", {-1}, "1", &n);
  const auto nm = static_cast<long long>(n[0]);
  auto scale = read_dataset<double>(file, group + "/scale", {nm}, "1");
  auto octants = read_dataset<std::uint32_t>(file, group + "/octants", {nm}, "1");
  auto centre = read_dataset<double>(file, group + "/centre_of_mass_m", {nm, 3}, "m");
  auto offsets = read_dataset<std::uint32_t>(file, group + "/support_offsets", {nm + 1}, "1");
  auto points = read_dataset<double>(file, group + "/support_points_m", {-1, 3}, "m");
  std::vector<std::string> keys;
  const std::string joined = read_string_attribute(file, group, "keys");
  for (std::size_t at = 0; at <= joined.size();) {
    const std::size_t end = std::min(joined.find(' ', at), joined.size());
    keys.push_back(joined.substr(at, end - at));
    at = end + 1;
  }
  if (keys.size() != entry.size()) throw InputError(where + ": not one key per mesh entry");
  for (std::size_t k = 0; k < entry.size(); ++k) {
    if (entry[k] >= entries.size() || !entries[entry[k]]->key.empty())
      throw InputError(where + ": mesh entry " + std::to_string(k) + " names entry " + std::to_string(entry[k]) +
                       ", out of range or named twice");
    if (keys[k].empty() || !(scale[k] > 0 && std::isfinite(scale[k])))
      throw InputError(where + ": mesh entry " + std::to_string(k) + " has an empty key or a scale that is not positive");
    if (offsets[k] >= offsets[k + 1] || offsets[k + 1] > points.size() / 3 || (k == 0 && offsets[0] != 0))
      throw InputError(where + ": '" + group + "/support_offsets' is not a partition of the support points");
    if (octants[k] != 1 && octants[k] != 8)
      throw InputError(where + ": mesh entry " + std::to_string(k) + " has " + std::to_string(octants[k]) +
                       " octants (1: mirror-symmetric, or 8)");
    model::PanMeshBody& m = *entries[entry[k]];
    m.key = keys[k];
    m.octants = static_cast<std::int32_t>(octants[k]);
    m.scale = scale[k];
    m.centre_of_mass_m = {centre[3 * k], centre[3 * k + 1], centre[3 * k + 2]};
    for (std::uint32_t i = offsets[k]; i < offsets[k + 1]; ++i) {
      if (!(std::isfinite(points[3 * i]) && std::isfinite(points[3 * i + 1]) && std::isfinite(points[3 * i + 2])))
        throw InputError(where + ": a support point is not finite");
      m.support_points_m.push_back({points[3 * i], points[3 * i + 1], points[3 * i + 2]});
    }
  }
}

}  // namespace clatter::io
