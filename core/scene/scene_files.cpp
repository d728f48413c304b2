#include "scene/scene_files.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/alpha_mask.h"
#include "scene/image_source.h"
#include "scene/mtl_scan.h"
#include "scene/texture.h"

namespace bounce {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// A .gltf's buffers that are files beside it (data: URIs are in its bytes).
// A file the loader already read as glTF parses here too; anything else
// (truncated since) adds nothing: its own bytes still change the hash.
void add_gltf_buffers(const fs::path& gltf, std::vector<fs::path>& files) {
  std::ifstream in(gltf, std::ios::binary);
  const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (!doc.is_object()) return;
  const auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return;
  for (const nlohmann::json& b : *buffers) {
    const auto uri = b.is_object() ? b.find("uri") : b.end();
    if (uri == b.end() || !uri->is_string()) continue;
    const std::string& u = uri->get_ref<const std::string&>();
    if (u.rfind("data:", 0) != 0) files.push_back(gltf.parent_path() / u);
  }
}

void add_companions(const fs::path& mesh_file, std::vector<fs::path>& files) {
  const std::string ext = lower_extension(mesh_file);
  if (ext == ".obj") {
    for (const fs::path& mtl : scene_internal::scan_obj_materials(mesh_file).libraries)
      files.push_back(mtl);
  } else if (ext == ".gltf") {
    add_gltf_buffers(mesh_file, files);
  }
}

void add_image(const ImageSource& source, std::vector<fs::path>& files) {
  if (source.is_file()) files.push_back(source.file());
}

}  // namespace

std::vector<fs::path> scene_source_files(const Scene& scene) {
  std::vector<fs::path> files;
  if (scene.path.empty()) return files;
  files.emplace_back(scene.path);
  for (const MeshInfo& mesh : scene.meshes) {
    if (mesh.source.empty()) continue;
    files.emplace_back(mesh.source);
    add_companions(mesh.source, files);
  }
  for (const Material& m : scene.materials) {
    if (m.texture) add_image(m.texture->source, files);
    if (m.alpha_mask) add_image(m.alpha_mask->source, files);
    if (m.emission_texture) add_image(m.emission_texture->source, files);
    if (m.normal_map) add_image(m.normal_map->source, files);
  }
  // Each once, keeping the first place: a mesh file named by several meshes
  // (one file, several pieces) or a texture shared by materials.
  std::vector<fs::path> unique;
  for (fs::path& f : files) {
    f = f.lexically_normal();
    if (std::find(unique.begin(), unique.end(), f) == unique.end()) unique.push_back(f);
  }
  return unique;
}

}  // namespace bounce
