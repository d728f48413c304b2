#include "folder/manifest_meshes.h"

namespace bounce {

std::vector<ManifestMesh> manifest_meshes(const LoadedBake& bake) {
  const std::string where = (bake.dir / bake_file::kManifest).string();
  const auto it = bake.manifest.find("meshes");
  if (it == bake.manifest.end()) return {};
  if (!it->is_array()) throw BakeReader::ReadError(where, "\"meshes\" must be an array");
  std::vector<ManifestMesh> out;
  std::size_t total = 0;
  for (std::size_t i = 0; i < it->size(); ++i) {
    const nlohmann::json& m = (*it)[i];
    const std::string key = "meshes[" + std::to_string(i) + "]";
    if (!m.is_object() || !m.contains("name") || !m["name"].is_string() ||
        !m.contains("patch_density") || !m["patch_density"].is_number() || !m.contains("patches") ||
        !m["patches"].is_number_unsigned() || !m.contains("area") || !m["area"].is_number())
      throw BakeReader::ReadError(where, key +
                                             " must be an object with a string \"name\", numbers "
                                             "\"patch_density\" and \"area\" and a count "
                                             "\"patches\"");
    ManifestMesh mesh;
    mesh.name = m["name"].get<std::string>();
    mesh.patch_density = m["patch_density"].get<float>();
    mesh.patches = m["patches"].get<std::size_t>();
    mesh.area = m["area"].get<double>();
    total += mesh.patches;
    out.push_back(std::move(mesh));
  }
  if (total != bake.size())
    throw BakeReader::ReadError(where, "\"meshes\" count " + std::to_string(total) +
                                           " patches, the bake has " + std::to_string(bake.size()));
  return out;
}

}  // namespace bounce
